#pragma once
// Temporary output files removed on SIGINT, SIGTERM and SIGHUP: an
// interrupted `abbe compensate -o OUT` (Ctrl-C, a killed job) leaves no
// OUT.tmp.XXXXXX behind. AtomicOutputFile registers its temporary file
// while it is being written; the handler (installed on the first
// registration) unlinks the registered files and ends the process with the
// signal's default action, as without it.
namespace abbe::io {

// Returns a slot for unregister_temp_file, or −1 if all slots are taken
// (then the file is not removed on a signal; exceptions still remove it).
int register_temp_file(const char* path) noexcept;
void unregister_temp_file(int slot) noexcept;

}  // namespace abbe::io
