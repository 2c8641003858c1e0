// OpenCL status codes as names, and the conversion of OpenCL failures into user-facing voxr::Error.
#pragma once

#include <CL/opencl.hpp>

#include <string>

namespace voxr {

const char* cl_status_name(cl_int status);

// "clEnqueueNDRangeKernel failed: CL_OUT_OF_RESOURCES (-5)" plus `context`, and for allocation failures a
// hint to use a smaller grid or fewer channels.
std::string describe_cl_error(const cl::Error& e, const std::string& context = {});

}  // namespace voxr
