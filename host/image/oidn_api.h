// The part of Intel Open Image Denoise's C API (OIDN 2.x, <OpenImageDenoise/oidn.h>) that
// geocold-cl uses, declared here because the library is loaded at run time (denoise.cpp) and
// its wheel on PyPI (pyoidn) ships no headers. Names, values and signatures follow the OIDN
// API documentation ("Open Image Denoise API": Devices, Filters, the RT filter's images
// color/albedo/normal/output and its hdr and cleanAux parameters) and oidn.h.
#pragma once

#include <cstddef>

extern "C" {

typedef struct OIDNDeviceImpl* OIDNDevice;
typedef struct OIDNFilterImpl* OIDNFilter;

// OIDNDeviceType
inline constexpr int OIDN_DEVICE_TYPE_CPU = 1;
// OIDNFormat
inline constexpr int OIDN_FORMAT_FLOAT3 = 3;
// OIDNError: 0 is OIDN_ERROR_NONE
inline constexpr int OIDN_ERROR_NONE = 0;

using oidnNewDevice_t = OIDNDevice (*)(int type);
using oidnCommitDevice_t = void (*)(OIDNDevice device);
using oidnSetDeviceInt_t = void (*)(OIDNDevice device, const char* name, int value);
using oidnGetDeviceError_t = int (*)(OIDNDevice device, const char** out_message);
using oidnReleaseDevice_t = void (*)(OIDNDevice device);
using oidnNewFilter_t = OIDNFilter (*)(OIDNDevice device, const char* type);
using oidnSetSharedFilterImage_t = void (*)(OIDNFilter filter, const char* name, void* dev_ptr, int format,
                                            size_t width, size_t height, size_t byte_offset,
                                            size_t pixel_byte_stride, size_t row_byte_stride);
using oidnSetFilterBool_t = void (*)(OIDNFilter filter, const char* name, bool value);
using oidnCommitFilter_t = void (*)(OIDNFilter filter);
using oidnExecuteFilter_t = void (*)(OIDNFilter filter);
using oidnReleaseFilter_t = void (*)(OIDNFilter filter);

}  // extern "C"
