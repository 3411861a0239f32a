/* Triangulation of a mesh file's polygons (internal to src/io), in place of
 * Assimp's aiProcess_Triangulate, whose ear clipping in 5.2 covers area
 * outside concave polygons of five or more corners (review s30: the
 * pentagon (0,0) (2,0) (2,2) (1,1) (0,2) came out with area 5 instead of 3,
 * one triangle filling its notch). See polygon.c. */
#ifndef PXI_IO_POLYGON_H
#define PXI_IO_POLYGON_H

#include <stdint.h>

/* Scratch for polygons of up to `cap` corners. */
typedef struct pxi_polygon_work {
    uint32_t cap;
    uint32_t *prev, *next;
    unsigned char *state;
    double *uv;
} pxi_polygon_work;

/* Triangulates polygon idx[0..n) (n >= 3 corners, indices into xyz, three
 * doubles per point) into n - 2 triangles, written to out as 3 indices
 * each, in the polygon's winding, using only its corners. The polygon is
 * taken in the plane its Newell normal is most across; a polygon of zero
 * area there (its corners on one line) becomes a fan. Returns 1, or 0 when
 * the polygon crosses itself in that plane (two edges cross, or no corner
 * can be cut off at some point; out is then incomplete). w must hold n
 * corners. */
int pxi_polygon_triangulate(const double *xyz, const uint32_t *idx, uint32_t n, pxi_polygon_work *w,
                            uint32_t *out);

#endif
