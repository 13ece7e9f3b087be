// The rasteriser kernel for avx512 (flags in CMakeLists.txt).
#define RASTER_KERNEL_LANES 16
#define RASTER_KERNEL_NAME rasterizeBatchAvx512
#define SAMPLE_KERNEL_NAME sampleEdgesAvx512
#define EDGE_DECISION_KERNEL_NAME bendingPixelsAvx512
#include "raster_kernel.inc"
#include "edge_sample_kernel.inc"
#include "edge_decision_kernel.inc"
