// The m4mesh command line: every subcommand, its options and its errors.
#include "cli/app.h"

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>

#include "cli/conform.h"
#include "cli/console.h"
#include "cli/convert.h"
#include "cli/decode3d.h"
#include "cli/demo.h"
#include "cli/encode3d.h"
#include "cli/gltf_compress.h"
#include "cli/inspect.h"
#include "cli/mesh2d.h"
#include "cli/metrics.h"
#include "cli/pictures.h"
#include "cli/rd.h"
#include "cli/serve.h"
#include "cli/track.h"
#include "common/error.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

int run_m4mesh(int argc, const char* const* argv) {
  CLI::App app{"m4mesh: MPEG-4-style mesh streams, 2D mesh objects and animated 3D meshes: encoders, decoders, conformance and tools"};
  app.require_subcommand(1);
  // Before or after the command: `m4mesh -q decode3d …` or `m4mesh decode3d … -q`.
  app.fallthrough();
  bool quiet = false, verbose = false, overwrite = false;
  app.add_flag("-q,--quiet", quiet, "print errors only: no summaries, notes, warnings or progress");
  app.add_flag("-v,--verbose", verbose, "print more detail");
  app.add_flag("-y,--overwrite", overwrite, "replace outputs that exist (refused otherwise)");

  EncodeArgs encode_args;
  CLI::App* encode_cmd = app.add_subcommand("encode", "Encode §9 text or OBJ frames into a mesh stream");
  encode_cmd->add_option("input", encode_args.input, "§9 decoded text, an OBJ file, a folder of OBJ frames or a pattern with '*'")->required();
  encode_cmd->add_option("-o,--output", encode_args.output, "output stream (.m4m)")->required();
  encode_cmd->add_option("--method", encode_args.method, "motion vector prediction: 2 (breadth-first, normative) or 1 (linear)")
      ->check(CLI::IsMember({1, 2}));
  encode_cmd->add_flag("--keep-order", encode_args.keep_order, "code Delaunay nodes in the input order instead of §10's");
  encode_cmd->add_option("--scale", encode_args.scale, "OBJ input: multiply x and y by this to get half pixels");
  encode_cmd->add_flag("--no-end-code", encode_args.no_end_code, "leave out mesh_object_end_code");
  encode_cmd->add_flag("--trace", encode_args.trace, "print every syntax element written");

  DecodeArgs decode_args;
  CLI::App* decode_cmd = app.add_subcommand("decode", "Decode a mesh stream to §9 text and print its MD5");
  decode_cmd->add_option("input", decode_args.input, "mesh stream")->required();
  decode_cmd->add_option("-o,--output", decode_args.output, "§9 text output (written only when decoding succeeds)");
  decode_cmd->add_option("--method", decode_args.method, "motion vector prediction: 2 or 1")->check(CLI::IsMember({1, 2}));
  decode_cmd->add_flag("--md5", decode_args.md5_only, "print only the MD5 of the decoded text");
  decode_cmd->add_flag("--keep-going", decode_args.keep_going,
                       "on an error, keep the planes decoded before it (the output then lacks its final 'end' line)");

  std::string trace_input;
  CLI::App* trace_cmd = app.add_subcommand("trace", "Print every syntax element of a 2D or 3D stream: bit offset, name, bit count, value");
  trace_cmd->add_option("input", trace_input, "mesh stream")->required();
  TraceSelection trace_selection;
  bool trace_fields_only = false;
  trace_cmd->add_option("--part", trace_selection.part, "only part K: the 3D unit K or the 2D plane K (-1: the object header); reads no further (the 3D header: through the first unit, where a map by neighbours is read)")
      ->check(CLI::Range(int64_t{-1}, int64_t{1} << 32));
  trace_cmd->add_flag("--fields-only", trace_fields_only, "no bins and raw bits of arithmetic-coded sections: fixed fields and byte sections only");

  std::string info_input;
  CLI::App* info_cmd = app.add_subcommand("info", "Summarise a 2D mesh stream plane by plane, or a 3D stream unit by unit");
  info_cmd->add_option("input", info_input, "mesh stream")->required();

  std::string check_input;
  CLI::App* check_cmd = app.add_subcommand("check", "List every violation of the specification in a stream (exit 0 only if conformant)");
  check_cmd->add_option("input", check_input, "mesh stream")->required();

  ConformOptions conform_options;
  CLI::App* conform_cmd = app.add_subcommand("conform", "Run the conformance suite through m4mesh's or another decoder");
  conform_cmd->add_option("suite", conform_options.suite,
                          "suite folder holding manifest.json (default: ./conformance, or the suite installed beside the tool)");
  conform_cmd->add_option("--decoder", conform_options.decoder_command,
                          "external decoder command: {in} stream, {out} output to write (§9 text; for the 3D suite every frame's "
                          "binary32 bytes, as decode3d -o FILE.f32), {method} 1 or 2; {in} and {out} are required");
  conform_cmd->add_option("--timeout", conform_options.timeout_seconds, "seconds the external decoder may take on one stream, then it is killed and the stream fails")
      ->capture_default_str();
  conform_cmd->add_flag("--coverage", conform_options.coverage, "after the table, what the valid streams reach of the catalog of normative items");

  std::string suite_folder;
  CLI::App* generate_cmd = app.add_subcommand("generate-suite", "Regenerate the conformance streams and manifest");
  generate_cmd->add_option("folder", suite_folder, "output folder")->required();

  Encode3dArgs encode3d_args;
  CLI::App* encode3d_cmd = app.add_subcommand("encode3d", "Encode an animated 3D mesh (OBJ, OFF or PLY frames, .m4seq, .pc2 or a glTF animation) into a mesh3d stream");
  encode3d_cmd->add_option("input", encode3d_args.input, "a folder of OBJ, OFF or PLY frames (one kind, numbered), a pattern with '*' (quoted), a .m4seq file (- : from standard input), a .pc2 file with its .obj, or a .glb or .gltf animation (morph targets or a skin)")->required();
  encode3d_cmd->add_option("-o,--output", encode3d_args.output, "output stream (.m4m)")->required();
  add_codec_options(*encode3d_cmd, encode3d_args);
  encode3d_cmd->add_flag("--no-hash", encode3d_args.no_hash, "leave out the decoded-frame hash units");
  encode3d_cmd->add_flag("--reorder", encode3d_args.reorder,
                         "number the vertices in coding order, not the input's: a smaller base mesh (decoders say so)");
  encode3d_cmd->add_option("--position-blend", encode3d_args.position_blend,
                           "the base mesh's positions: the known neighbours' mean blended into each parallelogram prediction, in sixteenths: "
                           "0 … 16, or auto (each base mesh's smallest)")
      ->capture_default_str();
  encode3d_cmd->add_option("--hash-group", encode3d_args.hash_group, "frames per group hash unit (1: an MD5 hash unit per frame)")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  encode3d_cmd->add_option("--fps", encode3d_args.fps, "frame rate (default 25); a glTF animation is sampled at it (default: at its keyframes, evenly spaced)")
      ->check(CLI::Range(0.001, 65535.0));
  encode3d_cmd->add_option("--mesh", encode3d_args.gltf_mesh, "glTF: the node or mesh to code, when the asset has several");
  encode3d_cmd->add_option("--animation", encode3d_args.gltf_animation, "glTF: the animation to bake, when the asset has several");
  encode3d_cmd->add_flag("--trace", encode3d_args.trace, "print every syntax element written, as `m4mesh trace` prints them");

  GltfCompressArgs gltf_args;
  gltf_args.encoding.codec = "auto";
  CLI::App* gltf_cmd = app.add_subcommand("gltf", "Compress a glTF file's morph-target animations into m4mesh streams (M4MESH_vertex_animation), keeping the rest of the file");
  gltf_cmd->add_option("input", gltf_args.input, "a .glb or .gltf file")->required();
  gltf_cmd->add_option("-o,--output", gltf_args.output, "the compressed file (.glb)")->required();
  add_codec_options(*gltf_cmd, gltf_args.encoding);
  gltf_cmd->add_flag("--bake-skins", gltf_args.bake_skins,
                     "also bake each animation that moves a skin into streams (with the node's morph targets), and take the skin from its node");
  gltf_cmd->add_flag("--required", gltf_args.required, "list the extension in extensionsRequired too (loaders without it refuse the file instead of showing the rest pose)");
  gltf_cmd->footer("Default: --codec auto --target-kg 0.1 (every codec, the smallest stream whose decoded KG error is at most 0.1 %).");

  Decode3dArgs decode3d_args;
  CLI::App* decode3d_cmd = app.add_subcommand("decode3d", "Decode a mesh3d stream into OBJ or PLY frames, a .m4seq, .pc2 or .f32 file");
  decode3d_cmd->add_option("input", decode3d_args.input, "mesh3d stream")->required();
  decode3d_cmd->add_option("-o,--output", decode3d_args.output, "a folder for OBJ frames, a .m4seq file, a .pc2 file (with the faces and frame 0 in the .obj beside it), PLY frames ('frames/*.ply': '*' becomes 0001, 0002, …), a .f32 file (every frame's binary32 x, y, z, little-endian), or - (standard output, --format); optional with --md5");
  decode3d_cmd->add_option("--format", decode3d_args.format, "with -o - (standard output): m4seq (default) or f32")->check(CLI::IsMember({"m4seq", "f32"}));
  decode3d_cmd->add_flag("--md5", decode3d_args.md5, "print the MD5 of every decoded frame's binary32 x, y, z (the 3D conformance hash)");
  decode3d_cmd->add_flag("--verify", decode3d_args.verify, "print every frame's hash check (OK, MISMATCH, NO HASH) and fail unless every frame was checked (a mismatch fails without it too)");
  decode3d_cmd->add_option("--frames", decode3d_args.frames, "frames A … B only (A:B, A: or :B): decoding starts at the last intra refresh at or before A (bfs3d, Affine-Octree --intra-period) and stops once the hash units covering B are read (with --verify: at the end)");
  decode3d_cmd->add_flag("--keep-going", decode3d_args.keep_going,
                         "on an error, keep the frames decoded before it (and say how many; the exit status is still 1)");
  decode3d_cmd->add_option("--max-bytes", decode3d_args.max_bytes,
                           "decode only the longest prefix of at most this many bytes that ends at a unit boundary (a progressive stream)");

  ProgressiveArgs progressive_args;
  CLI::App* progressive_cmd =
      app.add_subcommand("progressive", "The quality of a progressive stream after each unit: bytes received, KG error, PSNR, STED");
  progressive_cmd->add_option("stream", progressive_args.stream, "a progressive mesh3d stream (cpca-wpt)")->required();
  progressive_cmd->add_option("original", progressive_args.original, "the original frames, .m4seq or .pc2")->required();
  progressive_cmd->add_option("--step", progressive_args.step, "bytes between reports (default: a fortieth of the stream; 1: every unit)");

  MetricsArgs metrics_args;
  CLI::App* metrics_cmd = app.add_subcommand("metrics", "KG error, RMSE, max error, PSNR and STED between two sequences");
  metrics_cmd->add_option("original", metrics_args.original, "original frames or .m4seq")->required();
  metrics_cmd->add_option("decoded", metrics_args.decoded, "decoded frames, .m4seq, or a mesh3d stream")->required();
  metrics_cmd->add_option("--stream", metrics_args.stream, "the stream, to report bits per vertex per frame");
  metrics_cmd->add_flag("--json", metrics_args.json, "print one JSON object");
  metrics_cmd->add_flag("--csv", metrics_args.csv, "print CSV: a header and one row (with --per-frame, one row per frame)");
  metrics_cmd->add_flag("--per-frame", metrics_args.per_frame, "RMSE, max error and PSNR of every frame too");

  std::string convert_input, convert_output, convert_frames;
  double convert_fps = 25;
  CLI::App* convert_cmd = app.add_subcommand("convert", "Convert a frame sequence to .m4seq, .pc2 (+ .obj), PLY frames, a glTF animation or OBJ frames");
  convert_cmd->add_option("input", convert_input, "frames (a folder or a pattern), .m4seq, .pc2 with its .obj, or a .glb or .gltf animation")->required();
  convert_cmd->add_option("output", convert_output, "a .m4seq file, a .pc2 file (with its .obj), PLY frames ('frames/*.ply'), a .glb or .gltf animation, or a folder")
      ->required();
  convert_cmd->add_option("--fps", convert_fps, "a glTF animation's frames per second")->check(CLI::Range(0.001, 1000.0))->capture_default_str();
  convert_cmd->add_option("--frames", convert_frames, "the input's frames A … B only, counted from 0 (A:B, A: or :B): a clip cut from a sequence");
  GltfSelection convert_selection;
  convert_cmd->add_option("--mesh", convert_selection.mesh, "glTF input: the node or mesh to bake, when the asset has several");
  convert_cmd->add_option("--animation", convert_selection.animation, "glTF input: the animation to bake, when the asset has several");
  convert_cmd->add_option("--sample-fps", convert_selection.fps, "glTF input: bake at this many frames a second (keys not evenly spaced need it)")
      ->check(CLI::Range(0.001, 1000.0));

  DemoOptions demo_options;
  RenderArgs render_args;
  CLI::App* render_cmd = app.add_subcommand("render", "Draw a 2D mesh stream: its texture warped by every plane, as an animated GIF or one plane's PNG");
  render_cmd->add_option("input", render_args.input, "2D mesh stream")->required();
  render_cmd->add_option("-o,--output", render_args.output, "anim.gif (every plane) or frame.png (one plane)")->required();
  render_cmd->add_option("--texture", render_args.texture,
                         "a PNG laid on the I-plane's bounding box, one texel a pixel when they are the same size to a pixel (a texture from "
                         "track); the pictures then take its size (default: a checkerboard, pictures over every plane)");
  render_cmd->add_option("--plane", render_args.plane, "the plane a .png shows")->capture_default_str();
  render_cmd->add_flag("--wireframe", render_args.wireframe, "draw the triangles' edges over the picture");
  render_cmd->add_option("--fps", render_args.fps, "frames per second of a GIF (default: the texture's, as track writes it, else 25)");
  render_cmd->add_option("--size", render_args.size, "the picture's longer side in pixels (default: one pixel per half pixel of the mesh)");

  TrackArgs track_args;
  CLI::App* track_cmd = app.add_subcommand("track", "Turn a video into a 2D mesh object: a mesh on the first frame, its nodes tracked through the video (docs/tracking.md)");
  track_cmd->add_option("input", track_args.input, "a video FFmpeg reads, or an image sequence as FFmpeg names it (frames/%04d.png)")->required();
  track_cmd->add_option("-o,--output", track_args.output, "the 2D mesh stream")->required();
  track_cmd->add_option("--texture", track_args.texture, "write the first frame as the PNG texture `m4mesh render --texture` lays on the mesh");
  track_cmd->add_option("--uniform", track_args.uniform, "a uniform mesh of WxH-pixel cells (the default, 16x16)");
  track_cmd->add_option("--nodes", track_args.nodes, "a content-based Delaunay mesh of about N nodes");
  track_cmd->add_option("--mask", track_args.mask, "a PNG of the first frame, white where the object is: the Delaunay mesh covers the object only (with --nodes)");
  track_cmd->add_option("--frames", track_args.frames, "frames A … B only (A:B, A: or :B)");
  track_cmd->add_option("--search", track_args.search, "pixels a node's polygon is searched each way, frame to frame (block matching uses the same)")->capture_default_str();
  track_cmd->add_option("--levels", track_args.levels, "pyramid levels above full size, 0 … 4 (default: while the coarsest keeps 32 pixels a side)");
  track_cmd->add_option("--reference", track_args.reference, "match each frame against the first frame (the texture; no drift) or the previous one")
      ->check(CLI::IsMember({"first", "previous"}))
      ->capture_default_str();
  track_cmd->add_option("--border", track_args.border,
                        "border nodes follow the content under them (the mesh may uncover a strip at the frame's edge), or stay on the frame's edges "
                        "(the mesh always covers the frame: motion compensation)")
      ->check(CLI::IsMember({"follow", "frame"}))
      ->capture_default_str();
  track_cmd->add_option("--remesh", track_args.remesh,
                        "a new I-plane (the mesh laid out again) once over 2 % of the triangles have grown or shrunk past this factor of their area, or "
                        "the mesh covers under 80 % of the frame; 0: never")
      ->check(CLI::Range(0.0, 4.0))
      ->capture_default_str();
  track_cmd->add_option("--block", track_args.block, "block matching's block side in pixels (default: as many blocks as mesh nodes)");
  track_cmd->add_option("--report", track_args.report, "a CSV of every frame: bits, mesh coverage, PSNR of the rendering, of mesh and of block motion compensation");

  Render3dArgs render3d_args;
  CLI::App* render3d_cmd = app.add_subcommand("render3d", "Draw a 3D sequence or stream shaded; with --compare, beside its original, coloured by its error");
  render3d_cmd->add_option("input", render3d_args.input, "a sequence (frames, .m4seq, .pc2) or a mesh3d stream")->required();
  render3d_cmd->add_option("-o,--output", render3d_args.output, "frame.png (one frame) or anim.gif (every frame)")->required();
  render3d_cmd->add_option("--compare", render3d_args.compare, "the original: drawn on the left, the input on the right coloured by its per-vertex error");
  render3d_cmd->add_option("--frame", render3d_args.frame, "the frame a .png shows")->capture_default_str();
  render3d_cmd->add_option("--size", render3d_args.size, "pixels per view (square)")->capture_default_str();
  render3d_cmd->add_option("--azimuth", render3d_args.azimuth, "view direction around the vertical axis, degrees")->capture_default_str();
  render3d_cmd->add_option("--elevation", render3d_args.elevation, "view direction above the horizon, degrees")->capture_default_str();
  render3d_cmd->add_option("--fps", render3d_args.fps, "frames per second of a GIF")->capture_default_str();
  render3d_cmd->add_option("--view", render3d_args.view,
                           "follow: each frame centred at the largest frame's scale; fit: each frame filling the view; sequence: the whole sequence's box")
      ->transform(CLI::CheckedTransformer(std::map<std::string, View>{{"follow", View::kFollow}, {"fit", View::kFit}, {"sequence", View::kSequence}}))
      ->default_str("follow");
  render3d_cmd->add_option("--max-error", render3d_args.max_error, "the error coloured yellow (the top of the scale): one scale across pictures");

  RdArgs rd_args;
  CLI::App* rd_cmd = app.add_subcommand("rd", "Rate–distortion sweep: every 3D codec over its quality parameter, one row per point");
  rd_cmd->add_option("input", rd_args.input, "a sequence (frames, .m4seq, .pc2)")->required();
  rd_cmd->add_option("-o,--output", rd_args.output, "rows as .csv or .json (- : CSV on standard output)")->required();
  rd_cmd->add_option("--codecs", rd_args.codecs, "comma-separated codecs (default: every codec)")->delimiter(',');
  rd_cmd->add_flag("--json", rd_args.json, "JSON whatever the output's name");
  rd_cmd->add_option("--threads", rd_args.threads, "points measured at once (default 0: every core this process may use; the points do not depend on it, their times do)");

  CLI::App* demo_cmd = app.add_subcommand("demo", "Encode and decode an embedded waving-flag animation, check bit-exactness");
  demo_cmd->add_option("--cols", demo_options.cols, "nodes per row")->check(CLI::Range(2, 1023));
  demo_cmd->add_option("--rows", demo_options.rows, "nodes per column")->check(CLI::Range(2, 1023));
  demo_cmd->add_option("--frames", demo_options.frames, "planes")->check(CLI::Range(1, 100000));
  demo_cmd->add_option("--gif", demo_options.gif, "also draw the decoded planes warping a checkerboard into this animated GIF");

  ServeOptions serve_options;
  CLI::App* serve_cmd = app.add_subcommand("serve", "Serve the web player and analyzer (with your streams listed, or another site's folder) over HTTP, on loopback unless --host says otherwise");
  serve_cmd->add_option("paths", serve_options.paths,
                        "a folder to serve (default: the site the build made beside the tool), or streams (.m4m files, .glb or .gltf animations to play beside them, .png "
                        "textures of 2D streams, NAME.png with NAME.m4m; folders of them): the site with those streams listed in its player");
  serve_cmd->add_option("--port", serve_options.port, "TCP port (0: any free port; the address is printed)")->check(CLI::Range(0, 65535));
  serve_cmd->add_option("--host", serve_options.host, "address to listen on (default 127.0.0.1; 0.0.0.0 opens it to the network)");
  serve_cmd->add_option("--rate", serve_options.rate, "bytes per second of each stream (.m4m) sent, to watch a progressive stream arrive (default: unthrottled)");

  app.set_version_flag("--version", "m4mesh " M4MESH_VERSION);
  // Usage errors: one line, exit status 2 (help and --version: 0).
  if (argc >= 2 && argv[1][0] != '-' && app.get_subcommands([&](CLI::App* c) { return c->get_name() == argv[1]; }).empty()) {
    std::string names;
    for (const CLI::App* c : app.get_subcommands([](CLI::App*) { return true; })) names += (names.empty() ? "" : ", ") + c->get_name();
    std::fprintf(stderr, "error: unknown command '%s' (commands: %s)\n", argv[1], names.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    // Many surplus paths that exist: most likely a pattern the shell expanded.
    int files = 0;
    for (int i = 1; i < argc; ++i) files += std::filesystem::is_regular_file(argv[i]);
    if (files > 2)
      std::fprintf(stderr, "error: %d files where the command takes fewer: quote a pattern ('dir/*.obj') so that m4mesh, not the shell, expands it\n", files);
    else
      std::fprintf(stderr, "error: %s (m4mesh --help)\n", e.what());
    return 2;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "error: %s (m4mesh --help)\n", e.what());
    return 2;
  }
  if (quiet && verbose) {
    std::fprintf(stderr, "error: -q or -v, not both (m4mesh --help)\n");
    return 2;
  }
  console::set_level(quiet ? console::Level::kQuiet : verbose ? console::Level::kVerbose : console::Level::kNormal);
  console::set_overwrite(overwrite);
  try {
    if (*encode_cmd) return console::set_input(encode_args.input), run_encode(encode_args);
    if (*decode_cmd) return console::set_input(decode_args.input), run_decode(decode_args);
    if (*trace_cmd) {
      trace_selection.symbols = !trace_fields_only;
      return console::set_input(trace_input), run_trace(trace_input, trace_selection);
    }
    if (*info_cmd) return console::set_input(info_input), run_info(info_input);
    if (*check_cmd) return console::set_input(check_input), run_check(check_input);
    if (*conform_cmd) return run_conform(conform_options);
    if (*serve_cmd) return run_serve(serve_options);
    if (*generate_cmd) return run_generate_suite(suite_folder);
    if (*encode3d_cmd) return console::set_input(encode3d_args.input), run_encode3d(encode3d_args);
    if (*gltf_cmd) return console::set_input(gltf_args.input), run_gltf_compress(gltf_args);
    if (*decode3d_cmd) return console::set_input(decode3d_args.input), run_decode3d(decode3d_args);
    if (*metrics_cmd) return run_metrics(metrics_args);  // names each input as it reads it
    if (*progressive_cmd) return run_progressive(progressive_args);
    if (*convert_cmd) return console::set_input(convert_input), run_convert(convert_input, convert_output, convert_fps, convert_frames, convert_selection);
    if (*demo_cmd) return run_demo(demo_options);
    if (*rd_cmd) return console::set_input(rd_args.input), run_rd(rd_args);
    if (*render_cmd) return console::set_input(render_args.input), run_render(render_args);
    if (*render3d_cmd) return run_render3d(render3d_args);
    if (*track_cmd) return console::set_input(track_args.input), run_track(track_args);
  } catch (const Error& e) {
    std::cout.flush();
    // Input and file errors name their own file (and line); usage errors concern no file.
    if (e.kind() == ErrorKind::kInput || e.kind() == ErrorKind::kIo || e.kind() == ErrorKind::kUsage || console::input().empty())
      std::fprintf(stderr, "error: %s\n", e.what());
    else
      std::fprintf(stderr, "error: %s: %s\n", console::input().c_str(), e.what());
    return e.kind() == ErrorKind::kUsage ? 2 : 1;
  } catch (const std::exception& e) {
    // A failure of the system (file system, memory) rather than of the input.
    std::cout.flush();
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace m4mesh
