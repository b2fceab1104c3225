#pragma once
// The date that outputs carry (report footers, provenance blocks of
// compensated programs): now, or SOURCE_DATE_EPOCH (seconds since 1970)
// when that is set, for reproducible outputs.
#include <string>

namespace abbe::io {

// ISO 8601 UTC, e.g. "2026-11-25T21:00:00Z".
std::string utc_timestamp();

}  // namespace abbe::io
