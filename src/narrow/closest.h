/* Closest-point routines shared by the methods (internal). */
#ifndef PXI_CLOSEST_H
#define PXI_CLOSEST_H

#include "math/vec3.h"

static inline double pxi_clamp01(double x) { return x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x; }

/* Segment-segment closest points: parameters s on [p0,p1] and t on [q0,q1]
 * (both in [0,1]). Nearly parallel segments get the best of
 * well-conditioned candidates; exactly parallel overlapping ones the middle
 * of their overlap (closest.c). */
void pxi_segment_closest(px_vec3 p0, px_vec3 p1, px_vec3 q0, px_vec3 q1, double *s, double *t);

#endif
