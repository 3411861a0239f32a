/* px_chain: articulated chains, their forward kinematics and their links
 * as scene bodies (proxima/chain.h; REFERENCES §4.4).
 *
 * Forward kinematics as URDF defines it: T_k = T_parent * origin_k *
 * J_k(q_k), the joint motion J a rotation about the unit axis (Rodrigues'
 * formula) or a translation along it. The given rotations (origins,
 * geometry frames, base) are made orthonormal once, at creation, so that a
 * long chain's products stay rotations to rounding and px_scene_set_pose
 * (which allows 1e-6) never refuses them.
 *
 * Adjacency (after MoveIt's setup assistant, compute_default_collisions.cpp,
 * whose "adjacent" links are one joint apart, links without geometry
 * bypassed): each link with geometry is adjacent to its nearest ancestor
 * with geometry, the links without geometry between them bypassed. Unlike
 * MoveIt, two links are never adjacent through a common ancestor without
 * geometry (siblings, or root links through the base): such a group joins
 * subtrees that may move far apart (a table and a mobile base on
 * prismatic joints, two fingers on a frame), and excluding their pairs
 * would hide real collisions.
 *
 * Motion bounds (hpp-core's solid-solid-collision.cc computeCoefficients,
 * per link instead of per pair): a revolute joint j moves a point p at
 * |qd_j| times p's distance to its axis, which passes through link j's
 * origin; the distance from link j's origin to link k's is at most the sum,
 * over the links i between them, of |origin_i.t| plus the travel
 * max(|q_min_i|, |q_max_i|) of a prismatic joint i. A prismatic joint
 * moves everything below it at |qd_j|. The angular speed is the sum of the
 * revolute joints' speeds. A mimic joint (URDF <mimic>) takes the value
 * mult * q + off of the joint it follows: its limits are the image of that
 * joint's and its speed |mult| times that joint's, so the bounds hold for
 * it as for any joint. */
#include "proxima/chain.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "math/vec3.h"
#include "scene/scene_internal.h"

#define C_RANGE 0x1p250 /* the scene's translation range */

typedef struct clink {
    uint32_t parent, joint, dof; /* dof: index of its joint value, or UINT32_MAX */
    uint32_t mimic;              /* the link whose joint it follows, or UINT32_MAX */
    double mult, off;            /* a mimic joint's value: mult * q_mimic + off */
    px_pose origin, geometry;
    px_vec3 axis;
    double q_min, q_max, qd;
    const px_model *model;
    const px_convex *convex;
    uint32_t group, mask;
    void *user;
    /* Derived: */
    int moving;      /* a movable joint lies between the base and the link */
    px_vec3 center;  /* the link origin in the geometry frame */
    double speed, w; /* motion bounds */
} clink;

struct px_chain {
    px_allocator alloc;
    uint32_t n, dof;
    px_pose base;
    clink *link;
    uint32_t *dof_link; /* dof -> link */
    uint64_t *adj;      /* adjacent body pairs a << 32 | b, a < b, sorted */
    size_t n_adj, n_adj_cap;
};

static int has_geometry(const clink *l) { return l->model || l->convex; }

/* The nearest rotation-like matrix to r by Gram-Schmidt on its rows (r is
 * within 1e-6 of a rotation: px_pose_check passed). */
static void orthonormalise(double r[9]) {
    px_vec3 a = pxi_unit_safe(pxi_v(r[0], r[1], r[2]));
    px_vec3 b = pxi_v(r[3], r[4], r[5]);
    b = pxi_unit_safe(pxi_madd(b, a, -pxi_dot(a, b)));
    px_vec3 c = pxi_cross(a, b);
    const double o[9] = {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z};
    memcpy(r, o, sizeof o);
}

static px_pose compose(const px_pose *a, const px_pose *b) {
    px_pose out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.r[3 * i + j] =
                a->r[3 * i] * b->r[j] + a->r[3 * i + 1] * b->r[3 + j] + a->r[3 * i + 2] * b->r[6 + j];
    out.t = pxi_xform(a, b->t);
    return out;
}

/* The joint's motion J(q) (Rodrigues: R = I + sin q K + (1 - cos q) K^2). */
static px_pose joint_motion(const clink *l, double q) {
    px_pose j = px_pose_identity();
    px_vec3 a = l->axis;
    if (l->joint == PX_JOINT_PRISMATIC) {
        j.t = pxi_scale(a, q);
    } else if (l->joint == PX_JOINT_REVOLUTE) {
        double c = cos(q), s = sin(q), t = 1.0 - c;
        const double r[9] = {t * a.x * a.x + c,       t * a.x * a.y - s * a.z, t * a.x * a.z + s * a.y,
                             t * a.x * a.y + s * a.z, t * a.y * a.y + c,       t * a.y * a.z - s * a.x,
                             t * a.x * a.z - s * a.y, t * a.y * a.z + s * a.x, t * a.z * a.z + c};
        memcpy(j.r, r, sizeof r);
    }
    return j;
}

/* a * b for speeds and reaches, with 0 * inf = 0 (a joint that cannot move,
 * or a link on its axis). */
static double times(double a, double b) { return a == 0.0 || b == 0.0 ? 0.0 : a * b; }

static px_status check_link(const px_link_desc *d, uint32_t k, px_error *err) {
    if (d->parent != PX_CHAIN_ROOT && d->parent >= k)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_chain_create: link %u: parent %u is not an earlier link (nor PX_CHAIN_ROOT)", k,
                         d->parent);
    if (d->joint > PX_JOINT_PRISMATIC)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_create: link %u: unknown joint type %u", k,
                         d->joint);
    for (int i = 0; i < 4; ++i)
        if (d->reserved[i])
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_create: link %u: reserved[%d] must be 0",
                             k, i);
    if (d->model && d->convex)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_chain_create: link %u: both a model and a polytope (give one, or neither)", k);
    px_error e;
    px_status st = px_pose_check(&d->origin, &e);
    if (st != PX_OK) return pxi_error(err, st, "px_chain_create: link %u: origin: %s", k, e.message);
    if (!(pxi_max_abs(d->origin.t) <= C_RANGE))
        return pxi_error(err, PX_ERR_RANGE,
                         "px_chain_create: link %u: the origin's translation is beyond 2^250", k);
    if (d->model || d->convex) { /* the geometry frame of a link without geometry is ignored */
        st = px_pose_check(&d->geometry, &e);
        if (st != PX_OK) return pxi_error(err, st, "px_chain_create: link %u: geometry: %s", k, e.message);
        /* Half the range: the centre (the link origin in the geometry
         * frame, -R^T t) stays within the scene's. */
        if (!(pxi_max_abs(d->geometry.t) <= 0.5 * C_RANGE))
            return pxi_error(err, PX_ERR_RANGE,
                             "px_chain_create: link %u: the geometry's translation is beyond 2^249", k);
    }
    if (d->mimic > 1)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_create: link %u: mimic is %u (0 or 1)", k,
                         d->mimic);
    if (d->mimic && d->joint == PX_JOINT_FIXED)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_chain_create: link %u: a fixed joint cannot follow another (mimic)", k);
    if (d->mimic && (!isfinite(d->mimic_multiplier) || !isfinite(d->mimic_offset)))
        return pxi_error(err, PX_ERR_NON_FINITE,
                         "px_chain_create: link %u: the mimic multiplier %g or offset %g is not finite", k,
                         d->mimic_multiplier, d->mimic_offset);
    if (d->joint == PX_JOINT_FIXED) return PX_OK;
    if (!pxi_is_finite3(d->axis))
        return pxi_error(err, PX_ERR_NON_FINITE, "px_chain_create: link %u: the axis is not finite", k);
    if (!(pxi_max_abs(d->axis) > 0.0))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_create: link %u: the axis is zero", k);
    if (d->mimic) return PX_OK; /* its limits and speed come from the joint it follows */
    if (isnan(d->q_min) || isnan(d->q_max) || d->q_min > d->q_max || d->q_min == INFINITY ||
        d->q_max == -INFINITY)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_chain_create: link %u: joint limits [%g, %g] are NaN or empty", k, d->q_min,
                         d->q_max);
    if (isnan(d->max_speed) || d->max_speed < 0.0)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_chain_create: link %u: the speed limit %g must be >= 0 (INFINITY allowed)", k,
                         d->max_speed);
    return PX_OK;
}

/* Motion bounds of every link (see the file comment). */
static void derive_bounds(px_chain *c) {
    for (uint32_t k = 0; k < c->n; ++k) {
        clink *l = &c->link[k];
        px_pose gi;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) gi.r[3 * i + j] = l->geometry.r[3 * j + i];
        l->center = pxi_neg(pxi_rot(gi.r, l->geometry.t));
        l->speed = l->w = 0.0;
        l->moving = 0;
        /* Walk up: reach = the bound on the distance from the current
         * link's origin to link k's. */
        double reach = 0.0;
        for (uint32_t i = k; i != PX_CHAIN_ROOT; i = c->link[i].parent) {
            const clink *m = &c->link[i];
            if (m->joint == PX_JOINT_REVOLUTE) {
                l->speed += times(m->qd, reach);
                l->w += m->qd;
                l->moving = 1;
            } else if (m->joint == PX_JOINT_PRISMATIC) {
                l->speed += m->qd;
                l->moving = 1;
                reach += fmax(fabs(m->q_min), fabs(m->q_max));
            }
            reach += pxi_len_safe(m->origin.t);
        }
    }
}

static uint64_t adj_key(uint32_t a, uint32_t b) {
    return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

/* The adjacent pairs: each link with geometry and its nearest ancestor
 * with geometry (see the file comment), in increasing key order. */
static px_status find_adjacent(px_chain *c, px_error *err) {
    c->adj = pxi_alloc_array(&c->alloc, c->n, sizeof *c->adj);
    if (!c->adj) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_chain_create: out of memory");
    c->n_adj_cap = c->n;
    size_t q = 0;
    for (uint32_t k = 0; k < c->n; ++k) {
        if (!has_geometry(&c->link[k])) continue;
        uint32_t p = c->link[k].parent;
        while (p != PX_CHAIN_ROOT && !has_geometry(&c->link[p])) p = c->link[p].parent;
        if (p != PX_CHAIN_ROOT) c->adj[q++] = adj_key(k, p);
    }
    /* Insertion sort: keys (p << 32 | k) with p < k; nearly sorted already. */
    for (size_t i = 1; i < q; ++i) {
        uint64_t v = c->adj[i];
        size_t j = i;
        for (; j > 0 && c->adj[j - 1] > v; --j) c->adj[j] = c->adj[j - 1];
        c->adj[j] = v;
    }
    c->n_adj = q;
    return PX_OK;
}

px_chain *px_chain_create(const px_chain_desc *d, px_error *err) {
    pxi_error_clear(err);
    if (!d || !d->links)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_create: NULL argument"), (px_chain *)NULL;
    if (d->n_links == 0 || d->n_links > PX_CHAIN_MAX_LINKS)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_create: %u links (1 to %u allowed)",
                         d->n_links, PX_CHAIN_MAX_LINKS),
               (px_chain *)NULL;
    int bad = d->reserved0 != 0;
    for (int i = 0; i < 4; ++i) bad |= d->reserved[i] != 0;
    if (bad)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_create: reserved fields must be 0"),
               (px_chain *)NULL;
    px_error e;
    px_status st = px_pose_check(&d->base, &e);
    if (st != PX_OK) return pxi_error(err, st, "px_chain_create: base: %s", e.message), (px_chain *)NULL;
    if (!(pxi_max_abs(d->base.t) <= C_RANGE))
        return pxi_error(err, PX_ERR_RANGE, "px_chain_create: the base's translation is beyond 2^250"),
               (px_chain *)NULL;
    for (uint32_t k = 0; k < d->n_links; ++k)
        if (check_link(&d->links[k], k, err) != PX_OK) return NULL;
    for (uint32_t k = 0; k < d->n_links; ++k) {
        const px_link_desc *l = &d->links[k];
        if (!l->mimic) continue;
        uint32_t m = l->mimic_link;
        if (m >= d->n_links || m == k || d->links[m].joint == PX_JOINT_FIXED || d->links[m].mimic)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_chain_create: link %u: it follows link %u, which is not another link with a "
                             "movable joint following none (mimic_link)",
                             k, m),
                   (px_chain *)NULL;
    }
    px_allocator a;
    if (pxi_allocator_resolve(d->allocator, &a, err) != PX_OK) return NULL;
    px_chain *c = pxi_alloc(&a, sizeof *c);
    if (!c) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_chain_create: out of memory"), (px_chain *)NULL;
    memset(c, 0, sizeof *c);
    c->alloc = a;
    c->n = d->n_links;
    c->base = d->base;
    orthonormalise(c->base.r);
    c->link = pxi_alloc_array(&a, c->n, sizeof *c->link);
    c->dof_link = pxi_alloc_array(&a, c->n, sizeof *c->dof_link);
    if (!c->link || !c->dof_link) {
        px_chain_destroy(c);
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_chain_create: out of memory"), (px_chain *)NULL;
    }
    for (uint32_t k = 0; k < c->n; ++k) {
        const px_link_desc *s = &d->links[k];
        clink *l = &c->link[k];
        memset(l, 0, sizeof *l);
        l->parent = s->parent;
        l->joint = s->joint;
        l->origin = s->origin;
        l->geometry = s->model || s->convex ? s->geometry : px_pose_identity();
        orthonormalise(l->origin.r);
        orthonormalise(l->geometry.r);
        l->model = s->model;
        l->convex = s->convex;
        l->group = s->group;
        l->mask = s->mask;
        l->user = s->user;
        l->dof = l->mimic = UINT32_MAX;
        if (s->joint != PX_JOINT_FIXED) l->axis = pxi_unit_safe(s->axis);
        if (s->joint != PX_JOINT_FIXED && !s->mimic) {
            l->q_min = s->q_min;
            l->q_max = s->q_max;
            l->qd = s->max_speed;
            l->dof = c->dof;
            c->dof_link[c->dof++] = k;
        }
    }
    /* Mimic joints: limits and speed from the joint they follow (times():
     * a multiplier of 0 keeps the joint at its offset whatever the limits). */
    for (uint32_t k = 0; k < c->n; ++k) {
        const px_link_desc *s = &d->links[k];
        if (!s->mimic) continue;
        clink *l = &c->link[k];
        const clink *m = &c->link[s->mimic_link];
        l->mimic = s->mimic_link;
        l->mult = s->mimic_multiplier;
        l->off = s->mimic_offset;
        double lo = times(l->mult, m->q_min) + l->off, hi = times(l->mult, m->q_max) + l->off;
        l->q_min = l->mult < 0.0 ? hi : lo;
        l->q_max = l->mult < 0.0 ? lo : hi;
        l->qd = times(fabs(l->mult), m->qd);
    }
    derive_bounds(c);
    if (find_adjacent(c, err) != PX_OK) {
        px_chain_destroy(c);
        return NULL;
    }
    return c;
}

void px_chain_destroy(px_chain *c) {
    if (!c) return;
    px_allocator a = c->alloc;
    pxi_free(&a, c->link, (size_t)c->n * sizeof *c->link);
    pxi_free(&a, c->dof_link, (size_t)c->n * sizeof *c->dof_link);
    pxi_free(&a, c->adj, c->n_adj_cap * sizeof *c->adj);
    pxi_free(&a, c, sizeof *c);
}

uint32_t px_chain_link_count(const px_chain *c) { return c ? c->n : 0; }
uint32_t px_chain_dof(const px_chain *c) { return c ? c->dof : 0; }
uint32_t px_chain_joint_link(const px_chain *c, uint32_t i) {
    return c && i < c->dof ? c->dof_link[i] : PX_CHAIN_ROOT;
}

/* Joint values within their limits. */
static px_status check_q(const px_chain *c, const double *q, const char *fn, px_error *err) {
    if (c->dof && !q)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "%s: q is NULL (%u joint values)", fn, c->dof);
    for (uint32_t i = 0; i < c->dof; ++i) {
        const clink *l = &c->link[c->dof_link[i]];
        if (!isfinite(q[i]))
            return pxi_error(err, PX_ERR_NON_FINITE, "%s: joint value %u (link %u) is not finite", fn, i,
                             c->dof_link[i]);
        if (q[i] < l->q_min || q[i] > l->q_max)
            return pxi_error(err, PX_ERR_RANGE,
                             "%s: joint value %u (link %u) = %.17g is outside its limits [%g, %g]", fn, i,
                             c->dof_link[i], q[i], l->q_min, l->q_max);
    }
    return PX_OK;
}

static px_status forward(const px_chain *c, const double *q, px_pose *frames, px_pose *geometry,
                         const char *fn, px_error *err) {
    px_status st = check_q(c, q, fn, err);
    if (st != PX_OK) return st;
    for (uint32_t k = 0; k < c->n; ++k) {
        const clink *l = &c->link[k];
        const px_pose *parent = l->parent == PX_CHAIN_ROOT ? &c->base : &frames[l->parent];
        px_pose o = compose(parent, &l->origin);
        if (l->joint == PX_JOINT_FIXED) {
            frames[k] = o;
        } else {
            double v = l->mimic == UINT32_MAX ? q[l->dof] : l->mult * q[c->link[l->mimic].dof] + l->off;
            if (!isfinite(v))
                return pxi_error(err, PX_ERR_RANGE, "%s: link %u's mimic joint value is not finite", fn, k);
            px_pose j = joint_motion(l, v);
            frames[k] = compose(&o, &j);
        }
        px_pose g = compose(&frames[k], &l->geometry);
        if (!(pxi_max_abs(frames[k].t) <= C_RANGE) || !(pxi_max_abs(g.t) <= C_RANGE))
            return pxi_error(err, PX_ERR_RANGE, "%s: link %u's frame or geometry lies beyond 2^250", fn, k);
        if (geometry) geometry[k] = g;
    }
    return PX_OK;
}

/* forward() into scratch arrays of the chain's size (frames are needed for
 * the children even when the caller wants only the geometry): `stack` for
 * chains of up to C_STACK links, so that setting an arm's joints at every
 * step does not allocate, the chain's allocator beyond. */
#define C_STACK 32
static px_status forward_alloc(const px_chain *c, const double *q, px_pose stack[2 * C_STACK],
                               px_pose **frames, px_pose **geometry, const char *fn, px_error *err) {
    if (c->n <= C_STACK) {
        *frames = stack;
        *geometry = stack + C_STACK;
    } else {
        *frames = pxi_alloc_array(&c->alloc, c->n, sizeof **frames);
        *geometry = pxi_alloc_array(&c->alloc, c->n, sizeof **geometry);
        if (!*frames || !*geometry) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "%s: out of memory", fn);
    }
    return forward(c, q, *frames, *geometry, fn, err);
}

static void forward_free(const px_chain *c, px_pose *frames, px_pose *geometry) {
    if (c->n <= C_STACK) return;
    pxi_free(&c->alloc, frames, (size_t)c->n * sizeof *frames);
    pxi_free(&c->alloc, geometry, (size_t)c->n * sizeof *geometry);
}

px_status px_chain_forward(const px_chain *c, const double *q, px_pose *frames, px_pose *geometry,
                           px_error *err) {
    pxi_error_clear(err);
    if (!c) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_forward: the chain is NULL");
    /* Straight into the caller's arrays unless they overlap (the children
     * read their parents' frames). */
    size_t bytes = (size_t)c->n * sizeof(px_pose);
    int apart = !geometry || (const char *)frames + bytes <= (const char *)geometry ||
                (const char *)geometry + bytes <= (const char *)frames;
    if (frames && apart) return forward(c, q, frames, geometry, "px_chain_forward", err);
    px_pose stack[2 * C_STACK], *f, *g;
    px_status st = forward_alloc(c, q, stack, &f, &g, "px_chain_forward", err);
    if (st == PX_OK && frames) memcpy(frames, f, bytes);
    if (st == PX_OK && geometry) memcpy(geometry, g, bytes);
    forward_free(c, f, g);
    return st;
}

px_status px_chain_motion_bounds(const px_chain *c, uint32_t link, px_vec3 *center, double *speed, double *w,
                                 px_error *err) {
    pxi_error_clear(err);
    if (!c) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_motion_bounds: the chain is NULL");
    if (link >= c->n)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_motion_bounds: no link %u in the chain",
                         link);
    const clink *l = &c->link[link];
    if (center) *center = l->center;
    if (speed) *speed = l->speed;
    if (w) *w = l->w;
    return PX_OK;
}

int px_chain_adjacent(const px_chain *c, uint32_t a, uint32_t b) {
    if (!c || a >= c->n || b >= c->n || a == b) return 0;
    uint64_t k = adj_key(a, b);
    size_t lo = 0, hi = c->n_adj;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (c->adj[mid] < k)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < c->n_adj && c->adj[lo] == k;
}

/* Removes the bodies ids[0 .. upto-1] a failed px_chain_add_to_scene added. */
static void remove_added(const px_chain *c, px_scene *s, uint32_t *ids, uint32_t upto) {
    for (uint32_t k = 0; k < upto; ++k)
        if (ids[k] != PX_CHAIN_NO_BODY) {
            px_scene_remove_body(s, ids[k], NULL);
            ids[k] = PX_CHAIN_NO_BODY;
        }
    for (uint32_t k = upto; k < c->n; ++k) ids[k] = PX_CHAIN_NO_BODY;
}

px_status px_chain_add_to_scene(const px_chain *c, px_scene *s, const double *q, uint32_t *ids,
                                px_error *err) {
    pxi_error_clear(err);
    if (!c || !s || !ids)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_add_to_scene: NULL argument");
    px_pose stack[2 * C_STACK], *f, *g;
    px_status st = forward_alloc(c, q, stack, &f, &g, "px_chain_add_to_scene", err);
    uint32_t k = 0;
    for (; st == PX_OK && k < c->n; ++k) {
        const clink *l = &c->link[k];
        ids[k] = PX_CHAIN_NO_BODY;
        if (!has_geometry(l)) continue;
        px_body_desc bd;
        memset(&bd, 0, sizeof bd);
        bd.model = l->model;
        bd.convex = l->convex;
        bd.pose = g[k];
        bd.center = l->center;
        bd.max_speed = l->speed;
        bd.max_angular_speed = l->w;
        bd.group = l->group;
        bd.mask = l->mask;
        bd.flags = l->moving ? 0 : PX_BODY_STATIC;
        bd.user = l->user;
        px_error e;
        st = px_scene_add_body(s, &bd, &ids[k], &e);
        if (st != PX_OK) {
            ids[k] = PX_CHAIN_NO_BODY;
            pxi_error(err, st, "px_chain_add_to_scene: link %u: %s", k, e.message);
        }
    }
    for (size_t i = 0; st == PX_OK && i < c->n_adj; ++i) {
        uint32_t a = (uint32_t)(c->adj[i] >> 32), b = (uint32_t)c->adj[i];
        st = px_scene_exclude_pair(s, ids[a], ids[b], err);
    }
    if (st != PX_OK) remove_added(c, s, ids, k);
    forward_free(c, f, g);
    return st;
}

px_status px_chain_set_joints(const px_chain *c, px_scene *s, const uint32_t *ids, const double *q,
                              px_error *err) {
    pxi_error_clear(err);
    if (!c || !s || !ids)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_chain_set_joints: NULL argument");
    for (uint32_t k = 0; k < c->n; ++k) {
        const clink *l = &c->link[k];
        if (!has_geometry(l) || !l->moving) continue;
        if (!pxi_scene_body_movable(s, ids[k]))
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                             "px_chain_set_joints: link %u: body %u is not a moving body of the scene", k,
                             ids[k]);
    }
    px_pose stack[2 * C_STACK], *f, *g;
    px_status st = forward_alloc(c, q, stack, &f, &g, "px_chain_set_joints", err);
    for (uint32_t k = 0; st == PX_OK && k < c->n; ++k) {
        const clink *l = &c->link[k];
        if (has_geometry(l) && l->moving) st = px_scene_set_pose(s, ids[k], &g[k], err);
    }
    forward_free(c, f, g);
    return st;
}
