/* An external decoder for `m4mesh conform`, written against the installed
 * C interface alone (m4mesh.h, pkg-config m4mesh):
 *
 *     decode [--method N] [--chunk N] IN OUT
 *
 * decodes a 2D stream to §9 text or a 3D stream to binary32 frames,
 * pushing the file CHUNK bytes at a time (997) and writing planes and
 * frames as they come. Exits 1 with the error on standard error. */
#include <m4mesh.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const m4mesh_error *e) {
  fprintf(stderr, "decode: %s (kind %s, element '%s', frame %lld, unit %lld, bit %lld)\n", e->message, e->kind_name, e->element,
          (long long)e->frame, (long long)e->unit, (long long)e->bit_offset);
  return 1;
}

static unsigned char *read_file(const char *path, size_t *size) {
  FILE *f = fopen(path, "rb");
  unsigned char *data = NULL;
  size_t capacity = 0, n;
  *size = 0;
  if (!f) return NULL;
  do {
    if (*size == capacity) {
      unsigned char *grown = realloc(data, capacity = 2 * capacity + 65536);
      if (!grown) break;
      data = grown;
    }
    n = fread(data + *size, 1, capacity - *size, f);
    *size += n;
  } while (n > 0);
  fclose(f);
  return data;
}

/* Every plane ready, as §9 text. */
static m4mesh_status write_planes(m4mesh_decoder2d *decoder, FILE *out) {
  m4mesh_plane2d p;
  m4mesh_status status;
  uint32_t i;
  while ((status = m4mesh_decoder2d_next_plane(decoder, &p)) == M4MESH_OK) {
    fprintf(out, "plane %lld", (long long)p.index);
    if (!p.intra)
      fprintf(out, " P range=%u", p.range);
    else if (p.delaunay)
      fprintf(out, " I delaunay boundary=%u", p.boundary);
    else
      fprintf(out, " I uniform cols=%u rows=%u dx=%u dy=%u split=%u", p.cols, p.rows, p.dx, p.dy, p.split);
    fprintf(out, "\nnodes %u\n", p.node_count);
    for (i = 0; i < p.node_count; ++i) fprintf(out, "%d %d\n", p.nodes[2 * i], p.nodes[2 * i + 1]);
    if (!p.intra) continue;
    fprintf(out, "triangles %u\n", p.triangle_count);
    for (i = 0; i < p.triangle_count; ++i) fprintf(out, "%u %u %u\n", p.triangles[3 * i], p.triangles[3 * i + 1], p.triangles[3 * i + 2]);
  }
  return status;
}

static int decode2d(const unsigned char *data, size_t size, size_t chunk, int method, FILE *out) {
  m4mesh_decoder2d *decoder = m4mesh_decoder2d_new(method);
  size_t at;
  int result = 0;
  if (!decoder) return fprintf(stderr, "decode: no decoder for method %d\n", method), 1;
  fputs("m4mesh-decoded 1\n", out);
  for (at = 0; at < size && result == 0; at += chunk) {
    const size_t n = size - at < chunk ? size - at : chunk;
    if (m4mesh_decoder2d_push(decoder, data + at, n) != M4MESH_OK || write_planes(decoder, out) == M4MESH_ERROR) result = 1;
  }
  if (result == 0 && (m4mesh_decoder2d_finish(decoder) != M4MESH_OK || write_planes(decoder, out) != M4MESH_END)) result = 1;
  if (result != 0) fail(m4mesh_decoder2d_error(decoder));
  fputs("end\n", out);
  m4mesh_decoder2d_free(decoder);
  return result;
}

/* Every final frame ready, as binary32 x, y, z per vertex. */
static m4mesh_status write_frames(m4mesh_decoder3d *decoder, float **positions, size_t *capacity, uint32_t *next, FILE *out) {
  m4mesh_header3d header;
  m4mesh_status status;
  uint32_t index;
  if (m4mesh_decoder3d_header(decoder, &header) != M4MESH_OK) return M4MESH_AGAIN;
  if (*capacity < 3 * (size_t)header.vertices) {
    free(*positions);
    *capacity = 3 * (size_t)header.vertices;
    *positions = malloc(*capacity * sizeof(float) + 1);
    if (!*positions) return M4MESH_ERROR;
  }
  while ((status = m4mesh_decoder3d_next_frame(decoder, &index, *positions, *capacity)) == M4MESH_OK) {
    if (index != (*next)++) return fprintf(stderr, "decode: frame %u where %u was due\n", index, *next - 1), M4MESH_ERROR;
    fwrite(*positions, sizeof(float), 3 * (size_t)header.vertices, out);
  }
  return status;
}

static int decode3d(const unsigned char *data, size_t size, size_t chunk, FILE *out) {
  m4mesh_decoder3d *decoder = m4mesh_decoder3d_new();
  float *positions = NULL;
  size_t capacity = 0, at;
  uint32_t next = 0;
  int result = 0;
  if (!decoder) return fprintf(stderr, "decode: out of memory\n"), 1;
  for (at = 0; at < size && result == 0; at += chunk) {
    const size_t n = size - at < chunk ? size - at : chunk;
    if (m4mesh_decoder3d_push(decoder, data + at, n) != M4MESH_OK || write_frames(decoder, &positions, &capacity, &next, out) == M4MESH_ERROR)
      result = 1;
  }
  if (result == 0 && (m4mesh_decoder3d_finish(decoder) != M4MESH_OK || write_frames(decoder, &positions, &capacity, &next, out) != M4MESH_END))
    result = 1;
  if (result != 0 && m4mesh_decoder3d_error(decoder)->kind != M4MESH_ERROR_NONE) fail(m4mesh_decoder3d_error(decoder));
  free(positions);
  m4mesh_decoder3d_free(decoder);
  return result;
}

int main(int argc, char **argv) {
  int method = 2, a = 1, result;
  size_t chunk = 997, size;
  unsigned char *data;
  FILE *out;
  for (; a + 1 < argc && strncmp(argv[a], "--", 2) == 0; a += 2) {
    if (strcmp(argv[a], "--method") == 0) method = atoi(argv[a + 1]);
    else if (strcmp(argv[a], "--chunk") == 0) chunk = (size_t)atol(argv[a + 1]);
    else break;
  }
  if (argc - a != 2 || chunk == 0) return fprintf(stderr, "usage: decode [--method N] [--chunk N] IN OUT (m4mesh %s)\n", m4mesh_version()), 2;
  data = read_file(argv[a], &size);
  if (!data) return fprintf(stderr, "decode: cannot read %s\n", argv[a]), 1;
  out = fopen(argv[a + 1], "wb");
  if (!out) return fprintf(stderr, "decode: cannot write %s\n", argv[a + 1]), 1;
  /* 00 00 01 C4 starts a 3D stream, 00 00 01 BC a 2D one. */
  if (size >= 4 && data[3] == 0xC4)
    result = decode3d(data, size, chunk, out);
  else
    result = decode2d(data, size, chunk, method, out);
  free(data);
  return fclose(out) != 0 || result != 0;
}
