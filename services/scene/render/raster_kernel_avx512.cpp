// The rasteriser kernel for avx512 (flags in CMakeLists.txt).
#define RASTER_KERNEL_LANES 16
#define RASTER_KERNEL_NAME rasterizeBatchAvx512
#include "raster_kernel.inc"
