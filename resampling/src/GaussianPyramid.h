#pragma once
// The images registration works on: float32 copies of component 0, Gaussian-smoothed and
// decimated for the coarse levels. Internal to mvw_resampling.
#include "mvw/core/Volume.h"

namespace mvw::resampling::detail {

class WorkerPool;

// Component 0 of any volume as float32, same geometry and metadata.
Volume firstComponentAsFloat(const Volume& volume);

// Gaussian smoothing with standard deviation sigmaMm (per axis in that axis' voxels, at most
// a quarter of the axis' length; axes whose voxels are already coarser than about twice
// sigma are left alone), then keeping
// every s-th voxel along each axis, s = floor(sigmaMm / spacing) (at least 1), so the
// coarse image has about one voxel per sigma and no aliasing worth the name. The geometry
// follows: worldFromIndex' = worldFromIndex * diag(s). `image`: any scalar type, 1 component;
// the result is float32.
Volume smoothAndShrink(const Volume& image, double sigmaMm, WorkerPool& pool);

}  // namespace mvw::resampling::detail
