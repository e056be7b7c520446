// The one place the OpenCL C API is included. The project targets the OpenCL 1.2 API (every
// driver we run on, NVIDIA's included, implements it); 2.x calls are not used.
#pragma once

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
// clCreateCommandQueue is the 1.2 way to make a queue; headers targeting 2.0+ mark it deprecated.
#ifndef CL_USE_DEPRECATED_OPENCL_1_2_APIS
#define CL_USE_DEPRECATED_OPENCL_1_2_APIS
#endif
#include <CL/cl.h>
