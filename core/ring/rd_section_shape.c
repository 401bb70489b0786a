/*
 * rd_section_shape — the general cross-sections as polygons (rd_section.h):
 * each shape's outline in its b x h box, its checks, and the polygon's
 * area moments.
 *
 * Box frame: u radial from the inner edge (0) to the running face (b), v
 * axial from the bottom (0) to the top (h); outlines counter-clockwise.
 *   taper_face   (0,0) (b,0) (b - h tan a, h) (0,h): the lower edge at b
 *   inner_bevel  top: (0,0) (b,0) (b,h) (w,h) (0,h - t); bottom mirrored
 *   inner_step   top: (0,0) (b,0) (b,h) (w,h) (w,h - t) (0,h - t)
 *   keystone     top flank down to the inside by b tan a: (0,0) (b,0) (b,h)
 *                (0,h - b tan a); bottom mirrored; double: both
 *   polygon      the points, moved so that the box's corner is the origin
 * (w, t the shape's width and height, a its angle.)
 *
 * Moments: int u^a v^b dA = oint u^(a+1) v^b / (a + 1) dv (Green), each edge
 * by 3-point Gauss-Legendre, exact for the degree a + b + 1 <= 5.
 */
#include "rd_section.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double rd_section_polygon_moment(const double (*pts)[2], int n, int a, int b)
{
    static const double x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834},
                        w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        const double *p = pts[i], *q = pts[(i + 1) % n];
        double dv = q[1] - p[1];
        if (dv == 0.0)
            continue;
        for (int g = 0; g < 3; g++) {
            double t = 0.5 * (1.0 + x[g]);
            double u = p[0] + t * (q[0] - p[0]), v = p[1] + t * (q[1] - p[1]);
            sum += 0.5 * w[g] * pow(u, a + 1) * pow(v, b) / (a + 1) * dv;
        }
    }
    return sum;
}

/* Proper crossing or touching of segments pq and rs (not sharing an end). */
static int segments_meet(const double *p, const double *q, const double *r, const double *s)
{
    double d1 = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    double d2 = (q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0]);
    double d3 = (s[0] - r[0]) * (p[1] - r[1]) - (s[1] - r[1]) * (p[0] - r[0]);
    double d4 = (s[0] - r[0]) * (q[1] - r[1]) - (s[1] - r[1]) * (q[0] - r[0]);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return 1;
    /* collinear overlap or an end on the other segment */
    for (int k = 0; k < 4; k++) {
        const double *a = k < 2 ? r : p, *b = k < 2 ? s : q,
                     *c = (k & 1) ? (k < 2 ? q : s) : (k < 2 ? p : r);
        double d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if (d == 0.0 && fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) &&
            fmin(a[1], b[1]) <= c[1] && c[1] <= fmax(a[1], b[1]))
            return 1;
    }
    return 0;
}

/* A polygon's checks: no two non-neighbouring edges meet, an area. */
static int polygon_simple(const double (*pts)[2], int n, rd_error *err)
{
    for (int i = 0; i < n; i++)
        for (int j = i + 2; j < n; j++) {
            if (i == 0 && j == n - 1)
                continue; /* neighbours through the closing edge */
            if (segments_meet(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n]))
                return rd_error_set(err, RD_EINVAL, "/section/points_m",
                                    "@/section/points_m crosses itself: the edge from point "
                                    "%d to %d meets the edge from point %d to %d; allowed: a "
                                    "simple polygon (its edges meet only at their shared "
                                    "corners).",
                                    i, (i + 1) % n, j, (j + 1) % n);
        }
    return RD_OK;
}

/* The polygon moved into the box frame, counter-clockwise, checked. */
static int polygon_outline(const rd_section_spec *sp, double b, double h, double (*pts)[2], int *n,
                           rd_error *err)
{
    int m = sp->n_points;
    if (m < 3 || m > RD_SECTION_POINTS_MAX)
        return rd_error_set(err, RD_EINVAL, "/section/points_m",
                            "@/section/points_m has %d points; allowed 3 to %d.", m,
                            RD_SECTION_POINTS_MAX);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < m; i++)
        for (int k = 0; k < 2; k++) {
            if (!isfinite(sp->points[i][k]))
                return rd_error_set(err, RD_EINVAL, "/section/points_m",
                                    "@/section/points_m/%d holds a value that is not a "
                                    "finite number.",
                                    i);
            lo[k] = fmin(lo[k], sp->points[i][k]);
            hi[k] = fmax(hi[k], sp->points[i][k]);
        }
    if (fabs(hi[0] - lo[0] - b) > 1e-9 * b || fabs(hi[1] - lo[1] - h) > 1e-9 * h)
        return rd_error_set(err, RD_EINVAL, "/section/points_m",
                            "@/section/points_m spans %.6g m radially and %.6g m axially; "
                            "allowed: the box @/radial_width x @/axial_height = %.6g x "
                            "%.6g m (set them to the polygon's).",
                            hi[0] - lo[0], hi[1] - lo[1], b, h);
    for (int i = 0; i < m; i++) {
        pts[i][0] = sp->points[i][0] - lo[0];
        pts[i][1] = sp->points[i][1] - lo[1];
    }
    *n = m;
    int rc = polygon_simple((const double(*)[2])pts, m, err);
    if (rc != RD_OK)
        return rc;
    double area = rd_section_polygon_moment((const double(*)[2])pts, m, 0, 0);
    if (!(fabs(area) > 1e-6 * b * h))
        return rd_error_set(err, RD_EINVAL, "/section/points_m",
                            "@/section/points_m encloses an area of %.3g m^2; allowed: at "
                            "least 1e-6 of its box.",
                            fabs(area));
    for (int i = 0; area < 0 && i < m / 2; i++) { /* clockwise: reverse */
        double t[2] = {pts[i][0], pts[i][1]};
        memcpy(pts[i], pts[m - 1 - i], sizeof t);
        memcpy(pts[m - 1 - i], t, sizeof t);
    }
    return RD_OK;
}

/* A leg within (0, lim) m, else the error at `key` (in the ring's block). */
static int leg(double x, double lim, const char *key, const char *what, rd_error *err)
{
    if (isfinite(x) && x > 0.0 && x < lim)
        return RD_OK;
    return rd_error_set(err, RD_EINVAL, key,
                        "@%s = %g m is out of range: allowed above 0 and below %g m (%s); a "
                        "cut that large leaves no section.",
                        key, x, lim, what);
}

/* An angle whose cut b tan a (taper: h tan a) stays below `room`. */
static int angle_ok(double deg, double arm, double room, const char *what, rd_error *err)
{
    double lim = atan(room / arm) * 180.0 / M_PI;
    if (isfinite(deg) && deg > 0.0 && deg < lim && deg <= 45.0)
        return RD_OK;
    return rd_error_set(err, RD_EINVAL, "/section/angle_deg",
                        "@/section/angle_deg = %g deg is out of range: allowed above 0 and "
                        "below %.4g deg (%s).",
                        deg, fmin(lim, 45.0), what);
}

/* Mirrors a top-side outline to the bottom (v -> h - v), keeping it
 * counter-clockwise. */
static void mirror(double (*pts)[2], int n, double h)
{
    for (int i = 0; i < n; i++)
        pts[i][1] = h - pts[i][1];
    for (int i = 0; i < n / 2; i++) {
        double t[2] = {pts[i][0], pts[i][1]};
        memcpy(pts[i], pts[n - 1 - i], sizeof t);
        memcpy(pts[n - 1 - i], t, sizeof t);
    }
}

static int cut_shapes(int shape, const rd_section_spec *sp, double b, double h, double (*pts)[2],
                      int *n, rd_error *err)
{
    double w = sp->width, t = sp->height, a = sp->angle_deg * M_PI / 180.0;
    int rc = RD_OK;
    if (shape == RD_SECTION_TAPER_FACE) {
        rc = angle_ok(sp->angle_deg, h, b, "the running face's turn h tan(angle) below b", err);
        double q[4][2] = {{0, 0}, {b, 0}, {b - h * tan(a), h}, {0, h}};
        memcpy(pts, q, sizeof q), *n = 4;
        return rc;
    }
    if (shape == RD_SECTION_KEYSTONE) {
        double room = sp->double_sided ? 0.5 * h : h;
        rc = angle_ok(sp->angle_deg, b, room,
                      sp->double_sided ? "each flank's drop b tan(angle) below h / 2"
                                       : "the flank's drop b tan(angle) below h",
                      err);
        double drop = b * tan(a);
        double q[4][2] = {{0, sp->double_sided ? drop : 0}, {b, 0}, {b, h}, {0, h - drop}};
        memcpy(pts, q, sizeof q), *n = 4;
    } else {
        rc = leg(w, b, "/section/width_m", "the radial width b", err);
        rc = rc != RD_OK ? rc : leg(t, h, "/section/height_m", "the axial height h", err);
        if (shape == RD_SECTION_INNER_BEVEL) {
            double q[5][2] = {{0, 0}, {b, 0}, {b, h}, {w, h}, {0, h - t}};
            memcpy(pts, q, sizeof q), *n = 5;
        } else {
            double q[6][2] = {{0, 0}, {b, 0}, {b, h}, {w, h}, {w, h - t}, {0, h - t}};
            memcpy(pts, q, sizeof q), *n = 6;
        }
    }
    if (sp->side == 1 && !(shape == RD_SECTION_KEYSTONE && sp->double_sided))
        mirror(pts, *n, h);
    return rc;
}

int rd_section_outline(int shape, const rd_section_spec *sp, double b, double h, double (*pts)[2],
                       int *n, rd_error *err)
{
    *n = 0;
    if (sp->side != 0 && sp->side != 1)
        return rd_error_set(err, RD_EINVAL, "/section/side",
                            "@/section/side = %d is out of range: allowed 0 (top) or 1 "
                            "(bottom).",
                            sp->side);
    if (shape == RD_SECTION_POLYGON)
        return polygon_outline(sp, b, h, pts, n, err);
    if (shape < RD_SECTION_TAPER_FACE || shape > RD_SECTION_POLYGON)
        return rd_error_set(err, RD_EINVAL, "/section", "unknown section shape %d", shape);
    return cut_shapes(shape, sp, b, h, pts, n, err);
}

/* The polygon's chord on the line w = c (w the coordinate along the unit
 * vector e from the point o): the summed length of its pieces inside. */
static double chord(const double (*P)[2], int n, const double o[2], const double e[2], double c)
{
    double q[RD_SECTION_POINTS_MAX];
    int m = 0;
    for (int k = 0; k < n; k++) {
        const double *a = P[k], *b = P[(k + 1) % n];
        double wa = (a[0] - o[0]) * e[0] + (a[1] - o[1]) * e[1];
        double wb = (b[0] - o[0]) * e[0] + (b[1] - o[1]) * e[1];
        if ((wa < c) == (wb < c)) /* (half-open: a vertex on the line counts once) */
            continue;
        double t = (c - wa) / (wb - wa);
        double x = a[0] + t * (b[0] - a[0]) - o[0], y = a[1] + t * (b[1] - a[1]) - o[1];
        q[m++] = -x * e[1] + y * e[0]; /* along the line */
    }
    for (int i = 1; i < m; i++) /* insertion sort: a few crossings */
        for (int j = i; j > 0 && q[j - 1] > q[j]; j--) {
            double t = q[j];
            q[j] = q[j - 1];
            q[j - 1] = t;
        }
    double len = 0.0;
    for (int i = 0; i + 1 < m; i += 2)
        len += q[i + 1] - q[i];
    return len;
}

/* The energy method's shear form factor for a shear force along e
 * (Jourawski's shear flow across each line w = const, w from the
 * centroid o): kappa = A / I^2 int S(w)^2 / t(w) dw, t the chord, S the
 * first moment of the part beyond w, I = int w^2 t dw; the rectangle's
 * 6/5 and the circle's 10/9.  Midpoint rule on SHEAR_SLICES lines (second
 * order; 1e-7 on the rectangle). */
#define SHEAR_SLICES 4000
static double shear_form_factor(const double (*P)[2], int n, const double o[2], const double e[2])
{
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < n; k++) {
        double w = (P[k][0] - o[0]) * e[0] + (P[k][1] - o[1]) * e[1];
        lo = fmin(lo, w);
        hi = fmax(hi, w);
    }
    double dw = (hi - lo) / SHEAR_SLICES, t[SHEAR_SLICES], A = 0.0, I = 0.0, S = 0.0, k = 0.0;
    for (int i = 0; i < SHEAR_SLICES; i++) {
        double w = lo + (i + 0.5) * dw;
        t[i] = chord(P, n, o, e, w);
        A += t[i] * dw;
        I += w * w * t[i] * dw;
    }
    for (int i = SHEAR_SLICES - 1; i >= 0; i--) { /* S from the far side */
        double w = lo + (i + 0.5) * dw, f = w * t[i] * dw;
        if (t[i] > 0.0)
            k += (S + 0.5 * f) * (S + 0.5 * f) / t[i] * dw;
        S += f;
    }
    return A * k / (I * I);
}

double rd_section_principal_angle(double I_rr, double I_zz, double I_rz)
{
    double d = I_rr - I_zz;
    return d != 0.0 ? 0.5 * atan(2.0 * I_rz / d) : (I_rz != 0.0 ? copysign(M_PI / 4, I_rz) : 0.0);
}

void rd_section_shear_factors(const double (*P)[2], int n, double out[2])
{
    double A = rd_section_polygon_moment(P, n, 0, 0);
    double o[2] = {rd_section_polygon_moment(P, n, 1, 0) / A,
                   rd_section_polygon_moment(P, n, 0, 1) / A};
    double Irr = rd_section_polygon_moment(P, n, 2, 0) - A * o[0] * o[0],
           Izz = rd_section_polygon_moment(P, n, 0, 2) - A * o[1] * o[1],
           Irz = rd_section_polygon_moment(P, n, 1, 1) - A * o[0] * o[1];
    double a = rd_section_principal_angle(Irr, Izz, Irz), c = cos(a), s = sin(a);
    /* along each principal axis: in-plane p1 = (cos a, sin a), out-of-plane
     * p2 = (-sin a, cos a) */
    double p1[2] = {c, s}, p2[2] = {-s, c};
    out[0] = shear_form_factor(P, n, o, p1);
    out[1] = shear_form_factor(P, n, o, p2);
}

int rd_section_spec_solve(int shape, rd_section_spec *spec, double b, double h, rd_error *err)
{
    double pts[RD_SECTION_POINTS_MAX][2];
    int n;
    int rc = rd_section_outline(shape, spec, b, h, pts, &n, err);
    if (rc == RD_OK)
        rc = rd_section_torsion_solve((const double(*)[2])pts, n, &spec->J, &spec->J_error, err);
    if (rc == RD_OK) {
        double sf[2];
        rd_section_shear_factors((const double(*)[2])pts, n, sf);
        spec->shear_factor = sf[0];
        spec->shear_factor_axial = sf[1];
    }
    spec->solved = rc == RD_OK;
    return rc;
}
