/*
 * rd_bore_map — a bore whose shape changes along its height: the layered
 * "bore card" FE post-processors write (Fourier orders per axial layer) or
 * measured points (theta, z, dr) fitted per layer by least squares.
 *
 * Heights z are measured down from the top of the bore, m.  Layer i is a
 * whole bore (rd_bore, rd_liner.h): its diameter (0 = the ring's) and its
 * orders, r_i(theta) = D_i/2 + sum A_k cos(k (theta - phi_k)).  Between two
 * layers the radius is interpolated linearly in z at every angle:
 *     r(theta, z) = (1 - t) r_i(theta) + t r_{i+1}(theta),  t = (z - z_i) / (z_{i+1} - z_i),
 * which is exactly one bore again: each order's cosine and sine parts
 * (A cos k phi, A sin k phi) interpolated, and D too.  At a layer's height,
 * or between two layers that are the same bore, the bore IS that layer's
 * (copied, so the contact answer is bit for bit that of the plain bore).
 *
 * Points: dr is the radius' departure from the nominal bore radius D/2 at
 * angle theta (deg from the gap middle) and height z.  Points of equal z
 * (exactly) form a layer; each layer is fitted to
 *     dr(theta) = c_0 + sum_{k=1..K} (a_k cos k theta + b_k sin k theta)
 * by least squares (LAPACK dgels), K = fit_order, which needs 2K + 1
 * points at distinct angles per layer.  The layer's diameter is D + 2 c_0
 * (the mean radius per layer: taper, thermal growth), its orders 1..K with
 * A_k = hypot(a_k, b_k), phi_k = atan2(b_k, a_k) / k.  Points generated
 * from orders up to K are fitted back to rounding.
 *
 * Usage:
 *     rd_bore_map map;                           // caller-owned, no heap inside
 *     rc = rd_bore_points_validate(&pts, d, err) || rd_bore_map_fit(&pts, d, &map, err);
 *     rd_bore at;
 *     rc = rd_bore_map_at(&map, 0.02, d, &at, err); // the bore 20 mm down
 */
#ifndef RD_BORE_MAP_H
#define RD_BORE_MAP_H

#include "rd_error.h"
#include "rd_liner.h"

#define RD_BORE_LAYERS_MAX 50
#define RD_BORE_POINTS_MAX 100000
#define RD_BORE_Z_MAX      10.0 /* m: deepest layer */

typedef struct rd_bore_layer {
    double z;     /* m, down from the top of the bore */
    rd_bore bore; /* diameter (0 = the ring's) and orders */
} rd_bore_layer;

typedef struct rd_bore_map {
    int n_layers; /* 1..RD_BORE_LAYERS_MAX, z strictly increasing */
    rd_bore_layer layer[RD_BORE_LAYERS_MAX];
    double residual_rms; /* m: rms of dr - fit over all points (rd_bore_map_fit); NAN for
                            layers given as orders */
} rd_bore_map;

/* Measured points; the arrays are borrowed. */
typedef struct rd_bore_points {
    int n;
    const double *theta_deg, *z, *dr; /* deg from the gap middle, m down, m outward */
    int fit_order;                    /* K, 0..RD_BORE_ORDERS_MAX */
} rd_bore_points;

/* Range checks of given layers for a ring of diameter d, paths
 * "/layers/<i>/..." in the bore's block: 1..RD_BORE_LAYERS_MAX layers, z within 0 to
 * RD_BORE_Z_MAX m and strictly increasing, each layer a valid bore
 * (rd_bore_validate), and any two neighbours at most RD_BORE_ORDERS_MAX
 * distinct orders together (a height between them combines them). */
int rd_bore_map_validate(const rd_bore_map *m, double d, rd_error *err);

/* Range checks of points, paths "/points/..." in the bore's block: n 1..RD_BORE_POINTS_MAX,
 * theta within +-720 deg, z within 0..RD_BORE_Z_MAX m, |dr| at most 1 % of
 * d, fit_order 0..RD_BORE_ORDERS_MAX, at most RD_BORE_LAYERS_MAX distinct z,
 * and 2 fit_order + 1 distinct angles in every layer. */
int rd_bore_points_validate(const rd_bore_points *p, double d, rd_error *err);

/* Fits valid points (rd_bore_points_validate) about the nominal bore
 * diameter D (> 0): fills *m, layers in increasing z, residual_rms set.
 * A fitted layer that is not a valid bore is RD_EINVAL at
 * "/points/dr" (the bore's block); RD_ENOMEM, RD_ENUMERIC (LAPACK) otherwise. */
int rd_bore_map_fit(const rd_bore_points *p, double D, rd_bore_map *m, rd_error *err);

/* The bore at height z (m) of a valid map, for a ring of diameter d (a
 * layer's 0 diameter): RD_EINVAL at "/height" (the contact block) when z is outside
 * the first to the last layer. */
int rd_bore_map_at(const rd_bore_map *m, double z, double d, rd_bore *out, rd_error *err);

#endif
