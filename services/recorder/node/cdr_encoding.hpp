#pragma once
/// @file
/// The CDR bytes of a sample as its Fast DDS type support serialises it for a writer (and a DDS
/// reader receives it): the 4-byte encapsulation header (XCDR1) and the sample, padding bytes
/// zero. Written into a buffer the caller keeps, so that a recording reuses its buffers instead
/// of allocating a payload per sample, and without a type support object: constructing one
/// computes the type's largest serialised size, which is costly for types with unbounded
/// sequences (the Foxglove ones).

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/NotEnoughMemoryException.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace climbsim::recorder {

/// Replaces the content of `out` by the CDR bytes of `sample` (a type fastddsgen generated:
/// static getCdrSerializedSize, serialize(Cdr&)). Keeps `out`'s capacity: no allocation once
/// it has held a sample as large. std::runtime_error naming `what` if the sample does not fit
/// its own serialised size.
template <class Sample>
void encodeCdr(const Sample& sample, std::vector<std::uint8_t>& out, const char* what = "a sample") {
  constexpr std::size_t kEncapsulationBytes = 4;
  // Zeroed as a Fast DDS payload is (calloc): the alignment padding the serialiser skips is 0.
  out.assign(Sample::getCdrSerializedSize(sample) + kEncapsulationBytes, 0);
  eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char*>(out.data()), out.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
  try {
    cdr.serialize_encapsulation();
    sample.serialize(cdr);
  } catch (const eprosima::fastcdr::exception::NotEnoughMemoryException&) {
    throw std::runtime_error(std::string("recording: ") + what + " does not serialise");
  }
  out.resize(cdr.getSerializedDataLength());
}

}  // namespace climbsim::recorder
