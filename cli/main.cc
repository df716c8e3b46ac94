// m4mesh: encoder, decoder and tools for MPEG-4-style mesh bitstreams.
#include "cli/app.h"
#include "common/parallel.h"

int main(int argc, char** argv) {
  m4mesh::use_one_heap();
  return m4mesh::run_m4mesh(argc, argv);
}
