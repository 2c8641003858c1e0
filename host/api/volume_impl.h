// What a voxr::VoxelVolume holds (include/voxr/voxr.h): the job's result and its report. Internal to libvoxr.
#pragma once

#include "voxelize/voxelize_job.h"
#include "voxr/voxr.h"

namespace voxr {

struct VoxelVolume::Impl {
  GridSpec grid;
  VoxelizeResult result;
  VoxelizeReport report;
};

}  // namespace voxr
