// The one translation unit that compiles the MCAP library's implementation
// (common/third_party/mcap, header-only; see its README.md).
#define MCAP_IMPLEMENTATION
#include <mcap/reader.hpp>
#include <mcap/writer.hpp>
