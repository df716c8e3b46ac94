#include "cli/decode3d.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>

#include "cli/console.h"
#include "cli/sequence_files.h"
#include "cli/sequence_writer.h"
#include "codecs3d/registry.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/md5.h"
#include "decoder/mesh3d/container_decoder.h"
#include "mesh3d/frame_hash.h"

namespace m4mesh {

namespace {

using console::say;

}  // namespace

int run_decode3d(const Decode3dArgs& args) {
  const bool writes = !args.output.empty();
  if (!writes && !args.md5) throw usage_error("decode3d needs -o OUTPUT, or --md5");
  if (writes) refuse_overwriting(args.input, args.output, OutputForm::kFileOrFolder);
  const auto [first, last] = frame_range(args.frames);
  // A file is read unit by unit; standard input and a prefix are read whole.
  std::vector<uint8_t> whole;
  std::optional<ContainerSource> source;
  if (args.input == "-" || args.max_bytes > 0) {
    whole = read_file(args.input);
    if (args.max_bytes > 0) {
      const ContainerPrefix prefix = container_prefix(split_container(whole), whole.size(), args.max_bytes);
      if (prefix.units == 0)
        throw usage_error("--max-bytes " + std::to_string(args.max_bytes) + " holds no unit: the first ends later");
      say("prefix: %zu units, %llu of %zu bytes", prefix.units, static_cast<unsigned long long>(prefix.bytes), whole.size());
      whole.resize(prefix.bytes);
    }
    source.emplace(whole);
  } else {
    source = ContainerSource::open_file(args.input);
  }
  Decode3dOptions options;
  // A frame that differs from its hash unit is an error; --verify lists every frame's result first.
  options.hashes = args.verify ? HashCheck::kRecord : HashCheck::kRequire;
  const SequenceOutput form = writes ? sequence_output(args.output, true, args.format) : SequenceOutput::kF32;
  Mesh3dDecoder decoder(std::move(*source), options);
  const ObjectHeader& header = decoder.header();
  console::detail("%s: codec %s, %u vertices, %u faces, %u frames", args.input.c_str(), decoder.codec().name.c_str(), header.vertex_count,
                  header.face_count, header.frame_count);
  if (decoder.vertex_order() == kVertexOrderCoding)
    say("note: %s numbers its vertices in coding order (encode3d --reorder), not necessarily the input's", args.input.c_str());
  if (const uint32_t start = first > 0 ? decoder.seek(first) : 0; start > 0)
    console::detail("%s: decoding from the intra refresh at frame %u", args.input.c_str(), start);
  Md5 md5;  // of every frame's binary32 bytes: the 3D conformance hash
  console::Progress progress("decoding frame", header.frame_count);
  // The frames in the range, when the header tells how many (and no error may cut them short).
  std::optional<uint32_t> count;
  if (header.frame_count != 0 && !args.keep_going)
    count = first < header.frame_count ? std::min(last, header.frame_count - 1) - first + 1 : 0;
  std::unique_ptr<SequenceWriter> writer;  // made at the first frame written
  std::vector<Vec3> frame;
  std::vector<uint32_t> written;
  size_t checked = 0;  // written[0 … checked − 1] have been compared with their hash units
  bool failed = false;
  try {
    // Frames after the range are decoded until the hash units covering the range have been read (a group hash
    // follows its group's last frame), or with --verify to the end; those in the range are written.
    while (decoder.next_frame()) {
      progress.update(decoder.frame_index() + 1);
      if (decoder.frame_index() >= first && decoder.frame_index() <= last) {
        if (args.md5) {
          const std::vector<uint8_t> bytes = frame_bytes(decoder.positions());
          md5.update(bytes.data(), bytes.size());
        }
        written.push_back(decoder.frame_index());
        if (writes) {
          if (!writer)
            writer = sequence_writer(form, args.output,
                                     {header.vertex_count, decoder.faces(), count, static_cast<double>(header.frame_rate_num) / header.frame_rate_den});
          frame.resize(decoder.positions().size());
          for (size_t v = 0; v < frame.size(); ++v) frame[v] = {decoder.positions()[v][0], decoder.positions()[v][1], decoder.positions()[v][2]};
          writer->frame(decoder.frame_index(), frame);
        }
      }
      while (checked < written.size() && decoder.hash_result(written[checked])) ++checked;
      if (decoder.frame_index() >= last && checked == written.size() && !args.verify) break;
    }
  } catch (const Error& e) {
    if (!args.keep_going) throw;
    std::fprintf(stderr, "error: %s: %s\n", args.input.c_str(), e.what());
    failed = true;
  }
  progress.finish();
  if (written.empty() && failed) {
    std::fprintf(stderr, "%s: no frame decoded before the error; nothing written\n", args.input.c_str());
    return 1;
  }
  if (written.empty()) throw usage_error("--frames " + args.frames + ": the stream has no frame there");
  // Hash units may check a group of frames after its last: the results come
  // at the end, on standard error when the frames fill standard output.
  std::FILE* report = args.output == "-" ? stderr : stdout;
  size_t mismatches = 0;
  std::vector<uint32_t> unchecked;
  for (uint32_t f : written) {
    const std::optional<bool> ok = decoder.hash_result(f);
    if (args.verify) std::fprintf(report, "frame %u: %s\n", f, !ok ? "NO HASH" : *ok ? "OK" : "MISMATCH");
    if (!ok) unchecked.push_back(f);
    mismatches += ok == false;
  }
  if (args.verify && !failed) {
    std::fprintf(report, "verify: %zu mismatches, %zu frames without a hash\n", mismatches, unchecked.size());
    decoder.require_hashes_match();
    // --verify promises that every frame was checked: a frame without a hash fails it, and nothing is written.
    if (!unchecked.empty()) {
      std::fprintf(stderr,
                   "error: %s: --verify: %zu frames carry no hash to check (the first: frame %u): the stream was encoded with --no-hash, "
                   "or --frames starts inside a group whose hash covers frames not decoded; nothing written\n",
                   args.input.c_str(), unchecked.size(), unchecked.front());
      return 1;
    }
  }
  if (writer) writer->commit();
  if (failed) {
    std::fprintf(stderr, "%s: decoded %s before the error; %s %s\n", args.input.c_str(), console::counted(written.size(), "frame", "frames").c_str(),
                 writes ? args.output.c_str() : "no file", written.size() == 1 ? "holds it" : "holds them");
    return 1;
  }
  say("%s: %s of %s%s", writes ? args.output.c_str() : args.input.c_str(), console::counted(written.size(), "frame", "frames").c_str(),
      console::counted(decoder.header().vertex_count, "vertex", "vertices").c_str(), decoder.has_end_code() || args.max_bytes > 0 ? "" : " (warning: no end code)");
  if (args.md5) std::fprintf(report, "%s\n", md5.hex_digest().c_str());
  return 0;
}

}  // namespace m4mesh
