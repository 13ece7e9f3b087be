// The rasteriser kernel for generic (flags in CMakeLists.txt).
#define RASTER_KERNEL_LANES 4
#define RASTER_KERNEL_NAME rasterizeBatchGeneric
#include "raster_kernel.inc"
