// Replace a file so that readers see either the old file or the complete new one, never a
// truncated mix: write a sibling temp file, fsync it, rename it over the target (rename is
// atomic within a directory on POSIX), then fsync the directory so the rename survives a crash.
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>

namespace gc::detail {

// "<target>.tmp-<pid>": in the target's directory so the rename never crosses filesystems.
std::filesystem::path temp_path_for(const std::filesystem::path& target);

// Calls write_tmp(temp) to produce the file, then syncs and renames it over target. Any
// failure (an exception from write_tmp, or a failing system call) removes the temp file and
// throws OutputError "cannot write image '<target>': <reason>".
void replace_file_atomically(const std::filesystem::path& target,
                             const std::function<void(const std::filesystem::path& tmp)>& write_tmp);

// Creates (truncates) `path` and writes `bytes`, throwing OutputError with the errno text.
// `target` is the name the user knows, for the message.
void write_bytes(const std::filesystem::path& path, std::string_view bytes, const std::filesystem::path& target);

// The message prefix every output failure shares.
std::string cannot_write(const std::filesystem::path& target);

}  // namespace gc::detail
