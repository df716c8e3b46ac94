/* m4mesh's C interface: decode 2D and 3D mesh streams as their bytes
 * arrive, encode 3D sequences held in memory. Every function reports
 * errors as values (never an exception or an abort); a handle may be used
 * by one thread at a time, different handles by different threads.
 * docs/api.md describes each function with an example. */
#ifndef M4MESH_H
#define M4MESH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define M4MESH_API __attribute__((visibility("default")))
#else
#define M4MESH_API
#endif

#define M4MESH_VERSION_MAJOR 1
#define M4MESH_VERSION_MINOR 0
#define M4MESH_VERSION_PATCH 0

/* The library's version, "1.0.0". */
M4MESH_API const char *m4mesh_version(void);
/* The 3D format version the library reads and writes: 16 (format 1.0). */
M4MESH_API unsigned m4mesh_format_version(void);

typedef enum m4mesh_status {
  M4MESH_OK = 0,
  M4MESH_AGAIN = 1, /* nothing ready yet: push more bytes, or finish */
  M4MESH_END = 2,   /* every frame or plane has been handed out */
  M4MESH_ERROR = -1 /* the error says why; a failed decoder stays failed */
} m4mesh_status;

typedef enum m4mesh_error_kind {
  M4MESH_ERROR_NONE = 0,
  M4MESH_ERROR_TRUNCATED,          /* the data ends inside a syntax element */
  M4MESH_ERROR_MISSING_START_CODE, /* a start code was expected and not found */
  M4MESH_ERROR_BAD_STUFFING,       /* stuffing bits that are not '0' then '1's */
  M4MESH_ERROR_RESERVED_VALUE,     /* a value the format reserves */
  M4MESH_ERROR_OUT_OF_RANGE,       /* a value outside its range */
  M4MESH_ERROR_INVALID_CODE,       /* bits that are no code of their table */
  M4MESH_ERROR_TRAILING_DATA,      /* bytes after the end code */
  M4MESH_ERROR_GEOMETRY,           /* invalid Delaunay geometry (2D) */
  M4MESH_ERROR_STRUCTURE,          /* units, planes or frames out of order, a hash that does not match */
  M4MESH_ERROR_LIMIT,              /* an implementation limit (docs/) */
  M4MESH_ERROR_INPUT,              /* an encoder input that is not a valid sequence */
  M4MESH_ERROR_IO,                 /* the file system */
  M4MESH_ERROR_USAGE,              /* a bad argument or option */
  M4MESH_ERROR_INTERNAL            /* out of memory, or a bug: please report it */
} m4mesh_error_kind;

/* An error as m4mesh's command line reports it. */
typedef struct m4mesh_error {
  m4mesh_error_kind kind;
  const char *kind_name; /* "truncated", "out-of-range", …; "" with M4MESH_ERROR_NONE */
  char element[64];      /* the syntax element or option; "" when none */
  int64_t frame;         /* the 3D frame or the 2D plane; -1 when none */
  int64_t unit;          /* the 3D unit (its index in the stream); -1 when none */
  int64_t bit_offset;    /* in the stream (3D: in the unit's payload); -1 when none */
  char message[512];     /* the whole report, as the command line prints it */
} m4mesh_error;

/* ---- 3D decoding ---- */

typedef struct m4mesh_decoder3d m4mesh_decoder3d;

typedef struct m4mesh_header3d {
  char codec[32];       /* "bfs3d", "affine-octree", "lcc" or "cpca-wpt" */
  uint32_t frames;      /* 0: not given by the stream (live) */
  uint32_t vertices;
  uint32_t faces;
  double frame_rate;    /* frames per second */
  int progressive;      /* 1: units refine every frame (cpca-wpt) */
} m4mesh_header3d;

/* A decoder with no bytes yet; NULL when out of memory. Frames are
 * checked against the stream's hash units: a frame that differs is an
 * error (M4MESH_ERROR_STRUCTURE, element "frame_md5" or "group_md5", with
 * the hash unit and its digest's bit). A group hash unit follows its
 * group's last frame, so next_frame hands out the group's earlier frames
 * before the check; a caller that must not show an unchecked frame holds
 * them until the group's end (the encoder's hash_group). */
M4MESH_API m4mesh_decoder3d *m4mesh_decoder3d_new(void);
M4MESH_API void m4mesh_decoder3d_free(m4mesh_decoder3d *decoder);
/* The next bytes of the stream, any number; every unit they complete is
 * decoded now. Its time is in proportion to the bytes, whatever the size of
 * the pieces; bytes that cannot begin a 3D stream fail once 4 have
 * arrived. */
M4MESH_API m4mesh_status m4mesh_decoder3d_push(m4mesh_decoder3d *decoder, const uint8_t *data, size_t size);
/* The stream has ended: its last unit is decoded and the stream must be
 * whole (every frame decoded), else M4MESH_ERROR_TRUNCATED. */
M4MESH_API m4mesh_status m4mesh_decoder3d_finish(m4mesh_decoder3d *decoder);
/* The object header's facts; M4MESH_AGAIN until its bytes are pushed. */
M4MESH_API m4mesh_status m4mesh_decoder3d_header(const m4mesh_decoder3d *decoder, m4mesh_header3d *header);
/* The faces, 3 vertex indices each, into faces[0 … 3 × header.faces − 1]
 * (capacity: the array's length); M4MESH_AGAIN until the first base mesh
 * unit is decoded. */
M4MESH_API m4mesh_status m4mesh_decoder3d_faces(const m4mesh_decoder3d *decoder, uint32_t *faces, size_t capacity);
/* The next final frame in display order (no later unit can change it):
 * its index and x, y, z per vertex into positions (capacity: the array's
 * length, at least 3 × header.vertices). M4MESH_AGAIN when it needs more
 * bytes, M4MESH_END after the last frame of a finished stream. */
M4MESH_API m4mesh_status m4mesh_decoder3d_next_frame(m4mesh_decoder3d *decoder, uint32_t *index, float *positions, size_t capacity);
/* A progressive stream's frame as the units decoded so far refine it,
 * before it is final; *units: how many units it reflects. M4MESH_AGAIN
 * when the decoder holds no refinement of it (before the first unit, or
 * once it is final and waits for next_frame). */
M4MESH_API m4mesh_status m4mesh_decoder3d_peek_frame(const m4mesh_decoder3d *decoder, uint32_t index, float *positions, size_t capacity,
                                                     size_t *units);
/* Units decoded so far, hash units included. */
M4MESH_API size_t m4mesh_decoder3d_units(const m4mesh_decoder3d *decoder);
/* The error that failed the decoder (kind M4MESH_ERROR_NONE when none). */
M4MESH_API const m4mesh_error *m4mesh_decoder3d_error(const m4mesh_decoder3d *decoder);

/* ---- 2D decoding ---- */

typedef struct m4mesh_decoder2d m4mesh_decoder2d;

/* A decoded plane (its header's facts, then the mesh); its arrays stay
 * valid until the decoder's next call. */
typedef struct m4mesh_plane2d {
  int64_t index;              /* planes counted from 0 */
  int intra;                  /* 1: an I-plane (a new mesh), 0: a P-plane (motion) */
  int delaunay;               /* an I-plane: 1 Delaunay, 0 uniform */
  uint32_t cols, rows, dx, dy, split; /* a uniform I-plane's grid */
  uint32_t boundary;          /* a Delaunay I-plane's boundary nodes */
  uint32_t range;             /* a P-plane's motion_range_code */
  uint32_t node_count;
  const int32_t *nodes;       /* x, y per node, in half pixels */
  uint32_t triangle_count;
  const uint32_t *triangles;  /* 3 node indices each, canonical order */
} m4mesh_plane2d;

/* method: 2 (Method II, what streams use unless told otherwise) or 1
 * (Method I); the stream does not signal it. NULL when out of memory or
 * for another method. */
M4MESH_API m4mesh_decoder2d *m4mesh_decoder2d_new(int method);
M4MESH_API void m4mesh_decoder2d_free(m4mesh_decoder2d *decoder);
/* The next bytes of the stream; a plane is ready once the start code
 * after it has arrived. */
M4MESH_API m4mesh_status m4mesh_decoder2d_push(m4mesh_decoder2d *decoder, const uint8_t *data, size_t size);
/* The stream has ended. */
M4MESH_API m4mesh_status m4mesh_decoder2d_finish(m4mesh_decoder2d *decoder);
/* The next plane; M4MESH_AGAIN when it needs more bytes, M4MESH_END after
 * the last plane of a finished stream. */
M4MESH_API m4mesh_status m4mesh_decoder2d_next_plane(m4mesh_decoder2d *decoder, m4mesh_plane2d *plane);
M4MESH_API const m4mesh_error *m4mesh_decoder2d_error(const m4mesh_decoder2d *decoder);

/* ---- 3D encoding ---- */

typedef struct m4mesh_encode_options {
  const char *codec;         /* "bfs3d" (NULL), "affine-octree", "lcc", "cpca-wpt", or "auto": every codec at the target, the smallest kept */
  double target_kg;          /* > 0: the smallest stream whose KG error (%) is at most this */
  double target_psnr;        /* > 0: the smallest stream whose PSNR (dB) is at least this */
  uint64_t max_bytes;        /* > 0: cpca-wpt's stream budget (its max-bytes option) */
  int hashes;                /* 1: hash units of the decoded frames (the default) */
  double frame_rate;         /* frames per second; 0: 25 */
  const char *const *codec_options; /* NULL, or name, value, name, value, …, NULL: the codec's options ("bits", "12"), and
                                        the quality target "max-error", "E": no decoded vertex farther than E from its original */
} m4mesh_encode_options;

/* The defaults: bfs3d, no target, hash units, 25 frames per second. */
M4MESH_API void m4mesh_encode_options_init(m4mesh_encode_options *options);
/* A 3D stream of `frames` frames of `vertices` vertices (x, y, z per
 * vertex, frame after frame) and their faces (3 indices each). The stream
 * is allocated here: free it with m4mesh_free. error may be NULL. */
M4MESH_API m4mesh_status m4mesh_encode3d(const float *positions, uint32_t frames, uint32_t vertices, const uint32_t *faces, uint32_t face_count,
                                         const m4mesh_encode_options *options, uint8_t **stream, size_t *size, m4mesh_error *error);
M4MESH_API void m4mesh_free(void *memory);

#ifdef __cplusplus
}
#endif

#endif /* M4MESH_H */
