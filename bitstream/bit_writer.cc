#include "bitstream/bit_writer.h"

#include "common/error.h"

namespace m4mesh {

const std::vector<uint8_t>& BitWriter::bytes() const {
  if (!byte_aligned())
    throw Error(ErrorKind::kStructure, "", kNoPlane, static_cast<int64_t>(position()),
                "bit writer is not byte-aligned");
  return bytes_;
}

std::vector<uint8_t> BitWriter::take_bytes() {
  bytes();
  return std::move(bytes_);
}

}  // namespace m4mesh
