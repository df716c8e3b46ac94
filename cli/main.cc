// m4mesh: encoder, decoder and tools for MPEG-4-style mesh bitstreams.
#include "cli/app.h"

int main(int argc, char** argv) { return m4mesh::run_m4mesh(argc, argv); }
