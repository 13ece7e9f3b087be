// The rasteriser kernel for avx2 (flags in CMakeLists.txt).
#define RASTER_KERNEL_LANES 8
#define RASTER_KERNEL_NAME rasterizeBatchAvx2
#include "raster_kernel.inc"
