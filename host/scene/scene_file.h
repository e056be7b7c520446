// Reading the files a scene names (the scene itself, .mtl libraries, textures) as regular files
// only: a directory, a FIFO or a device such as /dev/stdin named by a scene must give a clear
// message, never a hang on a read that does not end.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gc {

// "" when `path` is a regular file (after following symlinks); otherwise why it cannot be read
// as one: "file not found", "is a directory, not a file", "is not a regular file (...)".
std::string why_not_regular_file(const std::filesystem::path& path);

// The whole file. Throws InputError "<path>: <why>" when it is not a regular file or cannot be
// opened or read.
std::vector<unsigned char> read_regular_file(const std::filesystem::path& path);

}  // namespace gc
