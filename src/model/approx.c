/* PX_PIECES_APPROXIMATE: each part of a mesh is cut into convex pieces
 * whose hulls stay within a tolerance of it (convexdecomp's pxcd_decompose:
 * recursive plane cuts chosen to lower the worst concavity, then a merge
 * pass; after CoACD, Wei et al., SIGGRAPH 2022), and every piece becomes a
 * leaf with a certified bound h.
 *
 * The decomposer's concavity is sampled, so it is not trusted: h is
 * measured again here by reach.c, against the part's solid when the part is
 * closed (cut caps lie inside it: distance 0) and against its triangles
 * when it is open. A piece whose certified h exceeds the tolerance is kept
 * (the bracket stays true, only wider) and counted in the model's max_h.
 *
 * The pieces of a part are certified on options.threads threads (the
 * calling thread and helpers; C11 <threads.h>). Each piece's h depends on
 * its hull and the part alone, so the results, stored by piece index, are
 * the same for any thread count. Helpers call no allocator (the user's may
 * not be thread-safe): the hulls and every helper's scratch are made on
 * the calling thread first. Only the calling thread reports progress; a
 * cancel it sees stops the helpers within a thousand or so evaluations. */
#include <float.h>
#include <math.h>
#include <stdatomic.h>
#include <string.h>
#include <threads.h>
#include <time.h>

#include "convex/convex.h"
#include "core/core.h"
#include "model/model.h"
#include "pxcd.h"

/* Progress over the whole mesh: parts weighted by their triangles. */
typedef struct progress {
    const px_model_options *o;
    double done, share; /* fraction finished before this part, this part's share */
    double last;        /* the last fraction reported: never goes back */
    int cancelled;
} progress;

/* Reports fraction f of the current part; returns nonzero once cancelled. */
static int report(progress *p, double f) {
    p->last = fmax(p->last, fmin(1.0, p->done + p->share * f));
    if (p->o->progress && p->o->progress(p->o->progress_user, p->last)) p->cancelled = 1;
    return p->cancelled;
}

/* A part's share: the decomposer's stages (cutting is most of it), then
 * certifying the pieces from R_CERTIFY on. */
#define R_CERTIFY 0.7

static int part_progress(void *user, int stage, double fraction) {
    double f = stage == PXCD_STAGE_CUT     ? 0.55 * fraction
               : stage == PXCD_STAGE_MERGE ? 0.55 + 0.1 * fraction
                                           : 0.65 + 0.05 * fraction;
    return report(user, f);
}

/* The part's triangle tree for measuring h, with its solid when closed. */
static px_model *part_tree(const px_allocator *alloc, const double *xyz, const uint32_t *tri,
                           const px_mesh_part *mp, px_error *err) {
    size_t n = (size_t)mp->triangle_count * 3;
    uint32_t *local = pxi_alloc_array(alloc, n, sizeof *local);
    uint32_t *part = pxi_alloc_array(alloc, mp->triangle_count, sizeof *part);
    px_model *tree = NULL;
    if (!local || !part) {
        pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    } else {
        for (size_t i = 0; i < n; ++i) local[i] = tri[3 * (size_t)mp->first_triangle + i] - mp->first_vertex;
        memset(part, 0, (size_t)mp->triangle_count * sizeof *part);
        uint8_t closed = (uint8_t)(mp->closed != 0);
        tree = pxi_model_from_triangles(xyz + 3 * (size_t)mp->first_vertex, mp->vertex_count, local,
                                        mp->triangle_count, part, &closed, 1, 0, alloc, err);
    }
    pxi_free(alloc, local, n * sizeof *local);
    pxi_free(alloc, part, (size_t)mp->triangle_count * sizeof *part);
    return tree;
}

static px_status pxcd_to_status(pxcd_status s) {
    switch (s) {
    case PXCD_OK: return PX_OK;
    case PXCD_OUT_OF_MEMORY: return PX_ERR_OUT_OF_MEMORY;
    case PXCD_CANCELLED: return PX_ERR_CANCELLED;
    case PXCD_INVALID_INPUT: return PX_ERR_INVALID_ARGUMENT;
    default: return PX_ERR_INTERNAL;
    }
}

/* Appends leaf `i` (piece of part p) to the arrays, growing them. */
static int grow(px_model *m, px_convex ***convex, uint32_t *cap, uint32_t need) {
    if (need <= *cap) return 1;
    uint32_t nc = *cap ? *cap : 16;
    while (nc < need) nc *= 2;
    pxi_mleaf *l = pxi_alloc_array(&m->alloc, nc, sizeof *l);
    px_convex **c = pxi_alloc_array(&m->alloc, nc, sizeof *c);
    if (!l || !c) {
        pxi_free(&m->alloc, l, (size_t)nc * sizeof *l);
        pxi_free(&m->alloc, c, (size_t)nc * sizeof *c);
        return 0;
    }
    if (m->n_leaves) {
        memcpy(l, m->leaves, (size_t)m->n_leaves * sizeof *l);
        memcpy(c, *convex, (size_t)m->n_leaves * sizeof *c);
    }
    pxi_free(&m->alloc, m->leaves, (size_t)*cap * sizeof *l);
    pxi_free(&m->alloc, *convex, (size_t)*cap * sizeof *c);
    m->leaves = l;
    *convex = c;
    *cap = nc;
    return 1;
}

/* The hull of a piece's points. Points a few ulps off a cut plane can make
 * faces double precision cannot hold (px_convex_create refuses them as too
 * thin); the piece is then replaced by the hull of the corners of the grid
 * cells (side s, a power of two) that hold its points: it contains the
 * piece, grows it by at most s sqrt 3 (which the certified h then counts),
 * and its corners are exact multiples of s, so its faces are not slivers.
 * s grows from 2^-30 of the piece's extent up to `max_s`. */
static px_convex *piece_hull(const double *xyz, size_t n, double max_s, const px_convex_options *co,
                             const px_allocator *alloc, px_error *e) {
    px_convex *c = px_convex_create(xyz, n, co, e);
    if (c || e->code != PX_ERR_DEGENERATE || n > ((size_t)1 << 22)) return c;
    px_vec3 lo, hi;
    pxi_box3(xyz, n, &lo, &hi);
    const double ext = pxi_max_abs(pxi_sub(hi, lo)), big = pxi_max2(pxi_max_abs(lo), pxi_max_abs(hi));
    double *corners = pxi_alloc_array(alloc, 8 * n, 3 * sizeof *corners);
    if (!corners) return NULL;
    px_error first = *e;
    for (double s = ldexp(1.0, ilogb(ext) - 30); s <= max_s && !c; s *= 16.0) {
        if (!(big / s < 0x1p50)) continue; /* cells must stay exact: try larger ones */
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 8; ++k)
                for (int j = 0; j < 3; ++j) {
                    double cell = floor(xyz[3 * i + j] / s) * s;
                    corners[3 * (8 * i + (size_t)k) + (size_t)j] = (k >> j) & 1 ? cell + s : cell;
                }
        c = px_convex_create(corners, 8 * n, co, e);
    }
    pxi_free(alloc, corners, 8 * n * 3 * sizeof *corners);
    if (!c) *e = first;
    return c;
}

/* Certifying one part's pieces on the calling thread and its helpers. */
typedef struct certify {
    const px_model *tree;
    px_convex *const *hulls;
    pxi_mleaf *leaves; /* results, by piece index */
    px_error *errs;    /* each piece's status (code) and message */
    uint32_t n;
    int solid;
    double floor;
    atomic_uint next;     /* the next piece to take */
    atomic_uint done;     /* pieces finished */
    atomic_uint finished; /* helpers that returned */
    atomic_int cancel;
    progress *pr; /* the calling thread's only */
} certify;

typedef struct worker {
    certify *c;
    void *scratch;
    size_t bytes;
    int caller; /* the calling thread: reports progress */
} worker;

/* Calling thread: reports the pieces done; nonzero once cancelled. */
static int certify_report(certify *c) {
    double f = R_CERTIFY + (1.0 - R_CERTIFY) * (double)atomic_load(&c->done) / (double)c->n;
    if (report(c->pr, f)) atomic_store(&c->cancel, 1);
    return atomic_load(&c->cancel);
}

static int certify_stop(void *user) {
    worker *w = user;
    return w->caller ? certify_report(w->c) : atomic_load(&w->c->cancel);
}

static void certify_run(worker *w) {
    certify *c = w->c;
    while (!atomic_load(&c->cancel)) {
        unsigned i = atomic_fetch_add(&c->next, 1u);
        if (i >= c->n) break;
        pxi_mleaf *leaf = &c->leaves[i];
        c->errs[i].code = pxi_part_reach_in(w->scratch, w->bytes, c->hulls[i], c->tree, c->solid, c->floor,
                                            certify_stop, w, &leaf->h, &leaf->h_overlap, &c->errs[i]);
        atomic_fetch_add(&c->done, 1u);
    }
}

static int certify_helper(void *user) {
    worker *w = user;
    certify_run(w);
    atomic_fetch_add(&w->c->finished, 1u);
    return 0;
}

/* Certifies the n hulls of part p (leaves m->leaves[m->n_leaves ..], which
 * get h and h_overlap) on up to `threads` threads. */
static px_status certify_pieces(px_model *m, const px_model *tree, px_convex *const *hulls, uint32_t n,
                                int solid, double floor, unsigned threads, progress *pr, uint32_t p,
                                const px_mesh_part *mp, px_error *err) {
    enum { MAX_THREADS = 64 };
    unsigned nt = threads < 1 ? 1 : threads > MAX_THREADS ? MAX_THREADS : threads;
    if (nt > n) nt = n;
    uint32_t planes = 0;
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t f = pxi_part_reach_planes(hulls[i]);
        planes = f > planes ? f : planes;
        m->leaves[m->n_leaves + i] = (pxi_mleaf){p, PXI_NONE, 0.0, 0.0};
    }
    if (n == 0) return PX_OK;
    const size_t bytes = pxi_part_reach_scratch_bytes(planes);
    worker w[MAX_THREADS];
    thrd_t helper[MAX_THREADS];
    certify c = {tree, hulls, m->leaves + m->n_leaves, NULL, n, solid, floor, 0, 0, 0, 0, pr};
    c.errs = pxi_alloc_array(&m->alloc, n, sizeof *c.errs);
    /* Every thread's scratch, here: as many threads as scratches made. */
    unsigned nw = 0;
    for (; c.errs && nw < nt; ++nw) {
        w[nw] = (worker){&c, pxi_alloc(&m->alloc, bytes), bytes, nw == 0};
        if (!w[nw].scratch) break;
    }
    px_status st = PX_OK;
    if (!c.errs || nw == 0) {
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    } else {
        for (uint32_t i = 0; i < n; ++i) c.errs[i] = (px_error){0};
        unsigned started = 0;
        while (1 + started < nw &&
               thrd_create(&helper[started], certify_helper, &w[1 + started]) == thrd_success)
            ++started;
        certify_run(&w[0]);
        /* Waits for the helpers, reporting progress now and then. */
        while (atomic_load(&c.finished) < started) {
            certify_report(&c);
            thrd_sleep(&(struct timespec){.tv_nsec = 10 * 1000 * 1000}, NULL);
        }
        for (unsigned k = 0; k < started; ++k) thrd_join(helper[k], NULL);
        if (atomic_load(&c.cancel) || certify_report(&c)) {
            st = pxi_error(err, PX_ERR_CANCELLED,
                           "px_model_create_from_mesh: cancelled by the progress callback");
        } else {
            /* The first failing piece, whatever thread measured it. */
            for (uint32_t i = 0; i < n && st == PX_OK; ++i)
                if (c.errs[i].code != PX_OK)
                    st = pxi_error(err, c.errs[i].code,
                                   "px_model_create_from_mesh: part %u ('%s'), piece %u: %s", p, mp->name, i,
                                   c.errs[i].message);
        }
    }
    for (unsigned k = 0; k < nw; ++k) pxi_free(&m->alloc, w[k].scratch, bytes);
    pxi_free(&m->alloc, c.errs, (size_t)n * sizeof *c.errs);
    return st;
}

/* Decomposes part p into leaves appended to m. */
static px_status approximate_part(px_model *m, const px_mesh *mesh, uint32_t p, double tolerance,
                                  unsigned threads, progress *pr, px_convex ***convex, uint32_t *cap,
                                  px_error *err) {
    px_mesh_part mp;
    px_mesh_get_part(mesh, p, &mp);
    const double *xyz = px_mesh_vertices(mesh);
    const uint32_t *tri = px_mesh_triangles(mesh);
    px_convex_options co;
    memset(&co, 0, sizeof co);
    co.allocator = &m->alloc;
    px_error e;
    if (mp.triangle_count == 0) {
        /* A point set stands for its hull, as with PX_PIECES_PARTS. */
        if (!grow(m, convex, cap, m->n_leaves + 1))
            return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
        px_convex *c = px_convex_create(xyz + 3 * (size_t)mp.first_vertex, mp.vertex_count, &co, &e);
        if (!c)
            return pxi_error(err, e.code, "px_model_create_from_mesh: part %u ('%s'): %s", p, mp.name,
                             e.message);
        (*convex)[m->n_leaves] = c;
        m->leaves[m->n_leaves++] = (pxi_mleaf){p, PXI_NONE, 0.0, 0.0};
        return PX_OK;
    }
    /* The decomposer takes the part's own vertices, moved to the centre of
     * their box (a part far from the origin would cut with lengths small
     * against its coordinates; near the centre the subtraction is exact),
     * and local indices; its pieces are moved back. */
    size_t n = (size_t)mp.triangle_count * 3;
    uint32_t *local = pxi_alloc_array(&m->alloc, n, sizeof *local);
    double *moved = pxi_alloc_array(&m->alloc, mp.vertex_count, 3 * sizeof *moved);
    if (!local || !moved) {
        pxi_free(&m->alloc, local, n * sizeof *local);
        pxi_free(&m->alloc, moved, (size_t)mp.vertex_count * 3 * sizeof *moved);
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    }
    for (size_t i = 0; i < n; ++i) local[i] = tri[3 * (size_t)mp.first_triangle + i] - mp.first_vertex;
    const double *pv = xyz + 3 * (size_t)mp.first_vertex;
    px_vec3 lo, hi;
    pxi_box3(pv, mp.vertex_count, &lo, &hi);
    const double centre[3] = {0.5 * lo.x + 0.5 * hi.x, 0.5 * lo.y + 0.5 * hi.y, 0.5 * lo.z + 0.5 * hi.z};
    for (uint32_t i = 0; i < mp.vertex_count; ++i)
        for (int j = 0; j < 3; ++j) moved[3 * i + j] = pv[3 * i + j] - centre[j];
    pxcd_decomp_options dopt;
    memset(&dopt, 0, sizeof dopt);
    dopt.tolerance = tolerance;
    dopt.threads = threads;
    dopt.progress = part_progress;
    dopt.user = pr;
    pxcd_decomp_result *res = NULL;
    char msg[256] = "";
    pxcd_status ds =
        pxcd_decompose(moved, mp.vertex_count, local, mp.triangle_count, &dopt, &res, msg, sizeof msg);
    pxi_free(&m->alloc, local, n * sizeof *local);
    pxi_free(&m->alloc, moved, (size_t)mp.vertex_count * 3 * sizeof *moved);
    for (size_t i = 0; ds == PXCD_OK && i < res->piece_count; ++i)
        for (size_t k = 0; k < 3 * res->pieces[i].vertex_count; ++k)
            res->pieces[i].vertices[k] += centre[k % 3];
    if (ds != PXCD_OK) {
        px_status st = pxcd_to_status(ds);
        if (st == PX_ERR_CANCELLED)
            return pxi_error(err, st, "px_model_create_from_mesh: cancelled by the progress callback");
        return pxi_error(err, st, "px_model_create_from_mesh: part %u ('%s'): decomposition failed: %s", p,
                         mp.name, msg);
    }
    px_status st = PX_OK;
    px_model *tree = part_tree(&m->alloc, xyz, tri, &mp, err);
    if (!tree) st = err ? err->code : PX_ERR_OUT_OF_MEMORY;
    uint32_t np = (uint32_t)res->piece_count, made = 0;
    if (st == PX_OK &&
        (res->piece_count > UINT32_MAX - m->n_leaves || !grow(m, convex, cap, m->n_leaves + np)))
        st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    /* The hulls, on this thread (they allocate). */
    px_convex **hulls = st == PX_OK ? *convex + m->n_leaves : NULL;
    for (; st == PX_OK && made < np; ++made) {
        const pxcd_decomp_piece *pc = &res->pieces[made];
        hulls[made] =
            piece_hull(pc->vertices, pc->vertex_count, 0.125 * tolerance * res->diagonal, &co, &m->alloc, &e);
        if (!hulls[made]) {
            st = pxi_error(err, e.code, "px_model_create_from_mesh: part %u ('%s'), piece %u: %s", p, mp.name,
                           made, e.message);
            break;
        }
        if (report(pr, R_CERTIFY))
            st = pxi_error(err, PX_ERR_CANCELLED,
                           "px_model_create_from_mesh: cancelled by the progress callback");
    }
    /* Bounds are refined to 5 % of the tolerance (absolute, in the part's
     * units), finer where a piece reaches farther. */
    if (st == PX_OK)
        st = certify_pieces(m, tree, hulls, np, mp.closed != 0, 0.05 * tolerance * res->diagonal, threads, pr,
                            p, &mp, err);
    if (st == PX_OK) {
        for (uint32_t i = 0; i < np; ++i) m->max_h = fmax(m->max_h, m->leaves[m->n_leaves + i].h_overlap);
        m->n_leaves += np;
    } else {
        for (uint32_t i = 0; i < made; ++i) px_convex_destroy(hulls[i]);
    }
    px_model_destroy(tree);
    pxcd_decomp_free(res);
    return st;
}

px_status pxi_model_approximate(px_model *m, const px_mesh *mesh, const px_model_options *options,
                                px_convex ***convex, px_error *err) {
    double tolerance = options->tolerance != 0.0 ? options->tolerance : PX_MODEL_DEFAULT_TOLERANCE;
    if (!isfinite(tolerance) || !(tolerance >= PX_MODEL_MIN_TOLERANCE && tolerance <= 1.0))
        return pxi_error(
            err, PX_ERR_INVALID_ARGUMENT,
            "px_model_create_from_mesh: options.tolerance %.17g is not in [%g, 1] (finer than %g of "
            "the diagonal: use PX_PIECES_TRIANGLES, which is exact)",
            options->tolerance, PX_MODEL_MIN_TOLERANCE, PX_MODEL_MIN_TOLERANCE);
    /* The models' range first: the decomposition would compute with
     * overflowing or vanishing lengths before the tree refused them. */
    px_status rs = pxi_model_check_range(px_mesh_vertices(mesh), px_mesh_vertex_count(mesh), 1, err);
    if (rs != PX_OK) return rs;
    uint32_t np = px_mesh_part_count(mesh), cap = 0;
    double total = 0.0;
    for (uint32_t p = 0; p < np; ++p) {
        px_mesh_part mp;
        px_mesh_get_part(mesh, p, &mp);
        total += (double)mp.triangle_count + 1.0;
    }
    *convex = NULL;
    m->n_leaves = 0;
    progress pr = {options, 0.0, 0.0, 0.0, 0};
    px_status st = PX_OK;
    for (uint32_t p = 0; p < np && st == PX_OK; ++p) {
        px_mesh_part mp;
        px_mesh_get_part(mesh, p, &mp);
        pr.share = ((double)mp.triangle_count + 1.0) / total;
        st = approximate_part(m, mesh, p, tolerance, options->threads, &pr, convex, &cap, err);
        pr.done += pr.share;
    }
    if (st == PX_OK && options->progress && options->progress(options->progress_user, 1.0))
        st =
            pxi_error(err, PX_ERR_CANCELLED, "px_model_create_from_mesh: cancelled by the progress callback");
    /* The model keeps exactly n_leaves leaves and hulls (its byte count and
     * the destroy call know no capacity). */
    uint32_t n = m->n_leaves;
    if (st == PX_OK && n == 0) st = pxi_error(err, PX_ERR_INTERNAL, "px_model_create_from_mesh: no pieces");
    pxi_mleaf *l = NULL;
    px_convex **c = NULL;
    if (st == PX_OK) {
        l = pxi_alloc_array(&m->alloc, n, sizeof *l);
        c = pxi_alloc_array(&m->alloc, n, sizeof *c);
        if (!l || !c) st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_model: out of memory");
    }
    if (st == PX_OK) {
        memcpy(l, m->leaves, (size_t)n * sizeof *l);
        memcpy(c, *convex, (size_t)n * sizeof *c);
    } else {
        for (uint32_t i = 0; i < n; ++i) px_convex_destroy((*convex)[i]);
        pxi_free(&m->alloc, l, (size_t)n * sizeof *l);
        pxi_free(&m->alloc, c, (size_t)n * sizeof *c);
        l = NULL;
        c = NULL;
        n = 0;
    }
    pxi_free(&m->alloc, m->leaves, (size_t)cap * sizeof *m->leaves);
    pxi_free(&m->alloc, *convex, (size_t)cap * sizeof **convex);
    m->leaves = l;
    m->n_leaves = n;
    *convex = c;
    m->bytes += (size_t)n * sizeof *l;
    return st;
}
