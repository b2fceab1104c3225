#pragma once

namespace abbe::cli {

// Keeps freed large buffers in the process's heap for the next allocation
// instead of handing each back to the system (docs/performance.md,
// "Whole process on 100 k points"). The diagnosis allocates many column
// blocks of n observations × k columns (tens of MB on 100 k points); with
// glibc's defaults each is a fresh mmap whose pages the kernel zeroes again.
// glibc only (mallopt); elsewhere nothing.
void keep_large_buffers_in_heap();

}  // namespace abbe::cli
