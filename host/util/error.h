// The exception types the library throws. Each carries a complete, user-facing message
// (what failed, on which file/device, and why); the CLI prints it as is and maps the kind
// to the exit code documented in `geocold-cl --help`. Library code never calls exit().
#pragma once

#include <stdexcept>
#include <string>

namespace gc {

enum class ExitCode : int {
    Ok = 0,
    Internal = 1,    // a bug: an unexpected exception
    Usage = 2,       // bad command line
    Input = 3,       // unreadable or malformed scene / texture / reference file
    Device = 4,      // no usable device, or an OpenCL / Vulkan failure
    Output = 5,      // the output image could not be written
    Mismatch = 6,    // a cross-check or consistency run found images that disagree
    Incomplete = 7,  // merge: partial images that overlap or leave samples missing
    Interrupted = 130,
};

class Error : public std::runtime_error {
public:
    Error(ExitCode code, const std::string& message) : std::runtime_error(message), m_code(code) {}
    ExitCode code() const { return m_code; }

private:
    ExitCode m_code;
};

// A scene or texture file that cannot be read or makes no sense. Name the file (and the
// line, for text formats) in the message: "scene.obj:12: face index 9 out of range (8 vertices)".
class InputError : public Error {
public:
    explicit InputError(const std::string& message) : Error(ExitCode::Input, message) {}
};

class DeviceError : public Error {
public:
    explicit DeviceError(const std::string& message) : Error(ExitCode::Device, message) {}
};

class OutputError : public Error {
public:
    explicit OutputError(const std::string& message) : Error(ExitCode::Output, message) {}
};

// Partial images that do not add up to a frame: a chunk in two files, or samples missing.
class IncompleteError : public Error {
public:
    explicit IncompleteError(const std::string& message) : Error(ExitCode::Incomplete, message) {}
};

class UsageError : public Error {
public:
    explicit UsageError(const std::string& message) : Error(ExitCode::Usage, message) {}
};

}  // namespace gc
