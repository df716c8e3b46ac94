// The 3D suite's input sequences: built with +, − and × of small
// rationals or with dyadic values only, so that every platform builds the
// same doubles; and the residual patterns that reach every prefix bin of
// a channel (syntax/mesh3d/residual.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/point3.h"
#include "common/random.h"
#include "mesh/topology.h"
#include "mesh3d/sequence.h"
#include "syntax/mesh3d/residual.h"

namespace m4mesh::suite3d {

// Inputs built with +, − and × of small rationals only, so that every
// platform builds the same doubles: the surface of a box (closed, n × n
// quads per side), a separate open sheet, and a vertex in no face, under a
// polynomial twist and wave.
MeshSequence box_and_sheet(int frames, int n);

// A flat sheet rotating in its plane by the exact rotation (3/5, 4/5) scaled down.
MeshSequence rotating_sheet(int frames);

// The faces of an n × rows sheet of quads, row by row, vertex (i, j)
// numbered j (n + 1) + i, each quad cut along the same diagonal.
std::vector<Triangle> sheet_faces(int n, int rows);

// A cloth-like flag: an n × n sheet in the plane y = 0 (its rest shape,
// frame 0), whose later frames carry a cubic wave travelling along x, and
// a vertex in no face. With `collapse`, one triangle on the coding path
// degenerates in the last frame (two of its vertices meet).
MeshSequence waving_flag(int frames, int n, bool collapse);

// A long strip of n × rows quads, flat in frame 0, then under a slow wave
// along x whose amplitude grows across the strip.
MeshSequence waving_strip(int frames, int n, int rows);

// An n × n sheet in the box's middle and `loose` vertices in no face
// beside it, which stay put and now and then (one time in `one_in`), each
// coordinate on its own, jump to ±2^−u · m/8 off their place (u from 2 to
// 23, m from 1 to 8) or back: residuals of many prefix lengths after a
// zero, a short and a long one. Two more vertices in no face hold the unit
// box. Dyadic values only, the same doubles everywhere.
MeshSequence spiky_sheet(int frames, int n, int loose, uint64_t seed, int one_in);

// A residual of each class of syntax/mesh3d/residual.h (a zero, a
// residual of prefix length 0, one of length 1, at order k = 0), each
// followed by ±2^e for e from 0 to max_e: pattern(class residual, ±2^e)
// for every pair, signs alternating.
template <class Pattern>
void for_each_prefix_pattern(int max_e, Pattern pattern) {
  int32_t sign = 1;
  for (int cls = 0; cls < syntax::ResidualCoder<1>::kClasses; ++cls)
    for (int e = 0; e <= max_e; ++e) {
      pattern(sign * cls, -sign * (int32_t{1} << e));
      sign = -sign;
    }
}

// Residuals that reach every prefix bin of a channel after each class: the
// patterns of for_each_prefix_pattern(), each after a run of zeros long
// enough for the channel's order k to return to 0 (the running sum decays
// by 1/16 per symbol, to below 16).
std::vector<int32_t> prefix_schedule();

// A sequence on the unit grid of 16 bits (the box 0 … 65,535 held by two
// vertices in no face, so that a grid step is 1) whose `loose` vertices in
// no face, coded directly one after the other, are offset from their place
// in frame 0 by `offset(f, v)` steps on each axis; a 2 × 2 sheet beside
// them stays put.
MeshSequence designed_loose(int frames, int loose, const std::function<int32_t(int, int)>& offset);

// A 2 × 2 sheet and, in no face, a chain of vertices in the middle of the
// unit grid of 16 bits (as designed_loose()), each one `schedule`'s next
// value of steps on every axis off the one before: the residuals of the
// base mesh's positions predicted by the previous vertex.
MeshSequence loose_chain(const std::vector<int32_t>& schedule);

// Separate quads on the unit grid of 16 bits (as designed_loose()), each
// two faces (a, b, c), (c, b, d) at the same place but for d, which is
// `schedule`'s next value of steps on every axis off the parallelogram
// b + c − a: the residuals of the base mesh's parallelogram prediction.
MeshSequence parallelogram_quads(const std::vector<int32_t>& schedule);

// Three vertices on the unit grid of 16 bits, so few that the root cell
// codes their motion directly, in index order, with contexts fresh per
// frame. Per pattern of for_each_prefix_pattern(), a frame where the first
// vertex moves by the class's residual and the second by ±2^e on every
// axis, then a frame back; the third holds the box.
MeshSequence direct_triples();

// Two clusters of 5 vertices on the unit grid of 19 bits, in opposite
// octants of the root cube, 2^17 apart within each, so that every
// reconstruction term is exact. Per class and prefix length e (as
// prefix_schedule()), a frame where the first cluster moves by the matrix
// whose 12 residuals from identity are the class's residual and the second
// by one whose residuals are ∓2^e, each its cell's exact fit (for k = 16,
// f = 14), then a frame back to the clusters' places.
MeshSequence matrix_pairs();

// The flag's rest shape in a file (the lcc codec's --reference takes one).
std::string rest_shape_file(const MeshSequence& flag);

MeshSequence moving_tetrahedron(int frames);

// Tight clusters of 6 vertices, in pairs 12, 20, 40 and 80 steps of a
// 24-bit grid apart, inside the unit box: on every odd frame one cluster
// of each pair moves rigidly and the other at random, and on even frames
// both return. Cells split down to depth 20, where the closest pair is a
// leaf of 12 vertices; rigid clusters met deeper than 15 are matrix leaves.
MeshSequence deep_clusters(int frames);

// Clusters of 6 vertices in cells of the octree: two in cells of `depth`
// whose vertices jump at random in every frame (leaves of more than 4
// vertices there, coded directly when depth is max_depth), and two pairs
// of sibling cells one level up, one cluster moving rigidly (a matrix leaf
// of more than 4 vertices above max_depth), the other at random.
MeshSequence clustered_jumps(int frames, int depth);

// What real meshes have, in one sequence numbered out of any traversal's
// order: a closed octahedron, an open sheet, two fans sharing a vertex, a
// third face on an edge, a degenerate face, a repeated face, a face turned
// the wrong way, and vertices in no face; coordinates small integers.
MeshSequence awkward_mesh(int frames);

// A wheel of 2k faces around a top vertex, whose rim is the top of k
// strips (arms) rising from a fan at the bottom; arm i is shorter by
// min(i, k − i), so that the traversal, spreading both ways around the
// fan, reaches every arm's top in the same wave. The top vertex then has
// an open half-edge per arm, and the wheel's faces between arms close on
// candidates 1 … 7, or, past the 8-candidate cut, far vertices. Last, a
// loose face (v, v, u) on the seed's third corner v and first corner u.
MeshSequence crown(int frames, int k, int length);

// An n × n grid whose quads split along either diagonal at random: vertex
// degrees from 2 to 8, so that gates meet most pairs of degrees, each pair
// and its mirror many times.
MeshSequence irregular_grid(int frames, int n);

// The same sequence with its vertices numbered at random.
void renumber_at_random(MeshSequence& s, uint64_t seed);

// The irregular grid, 16 × 16 = 2^8 vertices numbered at random (so that
// the gate's vertex predicts input numbers better than parallelograms),
// with loose faces: a degenerate one, and faces repeating a directed edge
// of the grid with another third vertex, so that parallelograms across
// those edges take the first face of the edge.
MeshSequence shuffled_grid(int frames);

// A chain of faces, each across an edge of the one before, whose third
// vertex is new or, half of the time, an earlier vertex at random: far
// vertices at every distance from the gate's (up to the vertex count),
// after far vertices near and far.
MeshSequence far_chain(int faces, uint64_t seed);

// Faces on few vertices at random, no directed edge twice: vertices with
// many open half-edges around them, so that gates meet 3 and more
// candidates at every pair of degrees and take every index.
MeshSequence dense_soup(uint32_t vertices, int faces, uint64_t seed);

}  // namespace m4mesh::suite3d
