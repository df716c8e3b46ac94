#include "syntax/mesh3d/entropy_io.h"

namespace m4mesh::syntax {

void entropy_error(ErrorKind kind, const char* element, const std::string& message, int64_t frame, uint64_t bit) {
  throw Error(kind, element, frame, static_cast<int64_t>(bit), message);
}

}  // namespace m4mesh::syntax
