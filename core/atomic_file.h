// Writing files so that a reader never sees a partial one: write to a temporary name in the same
// folder, then rename over the destination (atomic on POSIX file systems). On any failure the
// temporary is removed and rtdr::Error names the destination.
#pragma once

#include <functional>
#include <string>

namespace rtdr {

// Calls write(tmp_path), which must create the file at tmp_path or throw; then renames it to `path`.
void write_file_atomically(const std::string& path, const std::function<void(const std::string& tmp_path)>& write);

// The common case: a text or binary blob.
void write_text_file(const std::string& path, const std::string& contents);

}  // namespace rtdr
