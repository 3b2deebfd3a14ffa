#pragma once
// Geometry of a four-marker target from its six edge lengths (metres, target frame).
//
// Edge order everywhere: d01, d02, d03, d12, d13, d23 (marker indices 0..3).
// Face k is the triangle opposite marker k.
//
// "Face height" (the paper's H, Breitenmoser et al. 2011, Sec. III-A) is taken as
// the tetrahedron's altitude: the distance of marker k to the plane of face k,
//   h_k = 3 V / A_k.
// It is the strictest reading of the paper's "colinearity constraint which prevents
// the target to turn out too flat": h_k is zero for four coplanar markers, and it
// never exceeds the altitude of any triangle through marker k, so min h_k >= H
// also keeps every triangle's altitude (three colinear markers) >= H.
#include <array>

#include <Eigen/Core>

namespace tetrapulse::hardware {

using Edges = std::array<double, 6>;              // d01 d02 d03 d12 d13 d23, metres
using Markers = std::array<Eigen::Vector3d, 4>;   // positions, metres

// Marker pair (i, j) of edge e.
constexpr std::array<std::array<int, 2>, 6> kEdgeMarkers{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
// Edges of the face opposite marker k.
constexpr std::array<std::array<int, 3>, 4> kFaceEdges{{{3, 4, 5}, {1, 2, 5}, {0, 2, 4}, {0, 1, 3}}};

Edges edges_of(const Markers& markers);

// Signed area of a triangle with sides a, b, c (Kahan's stable Heron formula):
// negative, with magnitude sqrt(|16 A^2|) / 4, when the sides violate the triangle inequality.
double triangle_area(double a, double b, double c);

// Signed volume: sqrt(det G) / 6 from the Gram matrix of the edges at marker 0;
// negative (-sqrt(-det G) / 6) when no tetrahedron has these edges.
double tetrahedron_volume(const Edges& e);

// Altitudes h_k = 3 V / A_k (see above). Negative when the edges are not realisable,
// so a penalty on H - h_k keeps pointing towards realisable shapes.
std::array<double, 4> face_heights(const Edges& e);
double min_face_height(const Edges& e);

// Smallest altitude of the four triangles (a planar layout's colinearity measure).
// For planar points (a projection) this is the face height: their volume is zero.
double min_triangle_altitude(const Edges& e);

// Markers realising the edges: marker 0 at the origin, marker 1 on +x, marker 2 in
// the xy-plane (y > 0), marker 3 at z > 0. Requires min_face_height(e) > 0.
Markers embed(const Edges& e);

// Edge lengths of the markers' orthogonal projection onto the plane normal to `up` (unit).
Edges projected_edges(const Markers& markers, const Eigen::Vector3d& up);

// Volume of a regular tetrahedron with the same RMS edge length: 1 for a regular
// tetrahedron, 0 for a flat one.
double volume_ratio(const Edges& e);

}  // namespace tetrapulse::hardware
