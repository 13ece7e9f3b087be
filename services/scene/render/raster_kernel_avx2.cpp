// The rasteriser kernel for avx2 (flags in CMakeLists.txt).
#define RASTER_KERNEL_LANES 8
#define RASTER_KERNEL_NAME rasterizeBatchAvx2
#define SAMPLE_KERNEL_NAME sampleEdgesAvx2
#define EDGE_DECISION_KERNEL_NAME bendingPixelsAvx2
#include "raster_kernel.inc"
#include "edge_sample_kernel.inc"
#include "edge_decision_kernel.inc"
