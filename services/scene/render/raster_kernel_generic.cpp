// The rasteriser kernel for generic (flags in CMakeLists.txt).
#define RASTER_KERNEL_LANES 4
#define RASTER_KERNEL_NAME rasterizeBatchGeneric
#define SAMPLE_KERNEL_NAME sampleEdgesGeneric
#define EDGE_DECISION_KERNEL_NAME bendingPixelsGeneric
#include "raster_kernel.inc"
#include "edge_sample_kernel.inc"
#include "edge_decision_kernel.inc"
