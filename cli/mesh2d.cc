#include "cli/mesh2d.h"

#include <cstdio>
#include <iostream>
#include <optional>

#include "cli/console.h"
#include "cli/decode3d.h"
#include "cli/sequence_files.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "decoder/mesh_object_decoder.h"
#include "encoder/frame_input.h"
#include "encoder/mesh_object_encoder.h"
#include "mesh/decoded_text.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

namespace {

MotionMethod method_of(int method) { return method == 1 ? MotionMethod::kMethod1 : MotionMethod::kMethod2; }

bool is_decoded_text(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return false;
  char header[17] = {};
  const size_t n = std::fread(header, 1, 16, file);
  std::fclose(file);
  return n == 16 && std::string(header) == "m4mesh-decoded 1";
}

}  // namespace

int run_encode(const EncodeArgs& args) {
  refuse_trace_to_output(args.trace, args.output);
  refuse_overwriting(args.input, args.output);
  std::vector<MeshPlane> planes;
  if (args.input == "-" || is_decoded_text(args.input)) {
    const std::vector<uint8_t> bytes = read_file(args.input);
    planes = parse_decoded_text(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), args.input);
  } else {
    std::vector<std::string> unused;
    const std::vector<std::string> files = frame_files(args.input, {".obj"}, &unused);
    if (!unused.empty())
      console::say("warning: %s: %zu files not used (not .obj frames), %s%s", args.input.c_str(), unused.size(), unused.front().c_str(),
                   unused.size() > 1 ? ", …" : "");
    if (const std::string gaps = numbering_gaps_warning(args.input, files); !gaps.empty()) console::say("warning: %s", gaps.c_str());
    std::vector<ObjFrame> frames;
    console::Progress progress("reading frame", files.size());
    for (size_t k = 0; k < files.size(); ++k) {
      frames.push_back(read_obj(files[k]));
      progress.update(k + 1);
    }
    progress.finish();
    if (const std::string note = dropped_records_note(files.front(), frames.front().dropped, "x, y and faces"); !note.empty())
      console::say("note: %s", note.c_str());
    planes = planes_from_frames(frames, files, args.scale).planes;
  }
  Trace trace(std::cout);
  EncoderOptions options;
  options.method = method_of(args.method);
  options.keep_node_order = args.keep_order;
  options.end_code = !args.no_end_code;
  options.trace = args.trace ? &trace : nullptr;
  options.report = [&](const std::string& message) { console::say("note: %s: %s", args.input.c_str(), message.c_str()); };
  const EncodeResult result = encode(planes, options);
  write_file_atomically(args.output, std::string_view(reinterpret_cast<const char*>(result.stream.data()), result.stream.size()));
  console::say("%s: %zu bytes, %lld I-planes, %lld P-planes", args.output.c_str(), result.stream.size(),
               static_cast<long long>(result.intra_planes), static_cast<long long>(result.inter_planes));
  return 0;
}

int run_decode(const DecodeArgs& args) {
  refuse_overwriting(args.input, args.output, OutputForm::kFileOrFolder);
  const std::vector<uint8_t> stream = read_file(args.input);
  if (is_mesh3d_stream(stream)) {
    if (args.output.empty() || args.md5_only || args.keep_going)
      throw usage_error(args.input + ": a mesh3d stream: m4mesh decode3d " + args.input + " -o FOLDER/, FILE.m4seq or FILE.f32");
    Decode3dArgs three_d;
    three_d.input = args.input;
    three_d.output = args.output;
    return run_decode3d(three_d);
  }
  DecoderOptions options;
  options.method = method_of(args.method);
  Decoder decoder(stream, options);
  std::optional<AtomicFile> file;
  if (!args.output.empty()) file.emplace(args.output);
  DecodedTextWriter writer([&](std::string_view text) {
    if (file) file->write(text);
  });
  int64_t planes = 0;
  try {
    while (decoder.next()) {
      writer.plane(decoder.info(), decoder.nodes(), decoder.info().intra ? decoder.triangles() : std::span<const Triangle>{});
      ++planes;
    }
  } catch (const Error& e) {
    if (!args.keep_going) throw;
    std::fprintf(stderr, "error: %s: %s\n", args.input.c_str(), e.what());
    if (file) {
      writer.finish_incomplete();
      file->commit();
    }
    std::fprintf(stderr, "%s: decoded %s before the error%s\n", args.input.c_str(),
                 console::counted(static_cast<uint64_t>(planes), "complete plane", "complete planes").c_str(),
                 file ? ("; " + args.output + " holds " + (planes == 1 ? "it" : "them") + ", without the final 'end' line").c_str() : "");
    return 1;
  }
  const std::string md5 = writer.finish();
  if (file) file->commit();
  for (const syntax::Warning& w : decoder.warnings())
    console::say("warning: %s: bit %lld: %s", args.input.c_str(), static_cast<long long>(w.bit_offset), w.message.c_str());
  // The MD5 goes to standard error when the decoded text fills standard output.
  std::FILE* report = args.output == "-" ? stderr : stdout;
  if (args.md5_only)
    std::fprintf(report, "%s\n", md5.c_str());
  else
    std::fprintf(report, "%s  %s (%s)\n", md5.c_str(), args.input.c_str(), console::counted(static_cast<uint64_t>(planes), "plane", "planes").c_str());
  return 0;
}

}  // namespace m4mesh
