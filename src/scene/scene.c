/* px_scene: bodies, sweep-and-prune over fat boxes, and a priority queue of
 * pairs keyed by the earliest time they could come within the report
 * distance (seed 000 §3.6; REFERENCES §4.2, §4.3).
 *
 * Broad phase (I-COLLIDE, Cohen et al. 1995; the pair updates of Bullet's
 * btAxisSweep3): three sorted arrays of box endpoints, kept sorted by
 * insertion sort. A swap of a min with another body's max changes the
 * overlap of that one pair on that axis; the pair is added when the boxes
 * then overlap on the other two axes (tested on the endpoints' positions,
 * which follow the same total order as the sort) and removed when they stop
 * overlapping. Boxes are the body's world box grown by half the report
 * distance plus a slack: a body is re-sorted only when it leaves its fat
 * box, so slow bodies cost one box test per step.
 *
 * Scheduler (Lin's thesis §3.6; the safe time of REFERENCES §4.3): after a
 * query at t0 with distance d, the gap g = d - report - eps can close no
 * faster than u = s_A + s_B, the bodies' largest point speeds (linear speed
 * of the reference point plus angular speed times the radius about it), or
 * with acceleration bounds and known velocities no faster than
 * u0 + a (t - t0); the pair is due at t0 + tau, the time the bound reaches
 * g. An indexed binary heap on (due, a, b) pops the due pairs.
 *
 * Safety does not rest on the declared bounds: every pose set is measured
 * (a bound on the largest displacement of any point of the body, |dc| +
 * theta R, theta the rotation angle), and a body that moved more than its
 * bounds allow in a step makes all its pairs due now. A due pair compares
 * the poses now with those of its last query: while no point can have
 * moved as far as its gap, it is re-keyed without a query. So a pair is
 * measured before its distance can fall to the report distance, whatever
 * the poses do. (Bounds between two poses, never running sums: a sum that
 * once grew large would round small moves away.) */
#include "proxima/scene.h"

#include <float.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <threads.h>
#include <time.h>

#include "core/core.h"
#include "math/vec3.h"
#include "model/model.h"
#include "narrow/narrow.h"
#include "scene/scene_internal.h"

#define S_NONE UINT32_MAX
#define S_TOMB UINT32_MAX /* a removed body's endpoint (sep.id) */
#define S_PI 3.14159265358979323846
/* The fat box's slack, relative to the body's box half-diagonal. */
#define S_SLACK 0.125

/* Hot helpers that must be inlined (see prefetch_feature, move_ep). */
#if defined(__GNUC__)
#define S_PREFETCH(p) __builtin_prefetch(p)
#define S_INLINE static inline __attribute__((always_inline))
#define S_NOINLINE static __attribute__((noinline))
#else
#define S_PREFETCH(p) ((void)(p))
#define S_INLINE static inline
#define S_NOINLINE static
#endif

enum { K_CONVEX = 0, K_MODEL_MODEL = 1, K_MODEL_CONVEX = 2, K_CONVEX_MODEL = 3 };

/* Fields are in the order a due pair reads them: its re-key touches the
 * first cache line of each record only. */
typedef struct sbody {
    double travel;        /* sum of the displacement bounds of its pose changes, rounded up */
    double speed;         /* vmax + wmax * radius: bound on a point's speed */
    double accel;         /* amax + alphamax * radius: bound on a point's acceleration (0: none) */
    double s_now, s_prev; /* |v| + |w| radius given for this step and for the last one */
    double size;          /* half-diagonal of the body-frame box */
    uint8_t alive, dirty, added, vel_now, chain, fitted;
    double fit_travel; /* travel when the fat box was last checked */
    double fit_room;   /* how far the body could then move and stay in it */
    const px_model *model;
    const px_convex *convex;
    px_pose pose;   /* the pose the next step measures */
    px_pose last;   /* the pose of the last step */
    px_vec3 center; /* body frame */
    px_vec3 lo, hi; /* body-frame box */
    double radius;  /* largest distance from center to the body */
    px_vec3 sc;     /* bounding sphere: centre (body frame) and radius */
    double sr;
    px_vec3 ic; /* a polytope's inner ball (inner_center + origin, body frame; ir 0: none),
                 * copied here so that inner_overlap reads no polytope memory */
    double ir;
    double vmax, wmax;   /* speed bounds */
    double sk, sk_last;  /* skews (how far from rotations) of pose and last */
    double reach;        /* |sc| + 3 sr: bounds |body-frame point - origin| (frame_pad) */
    uint32_t first_excl; /* head of its list of exclusions (sexcl) */
    uint32_t dirty_at;   /* its place in `dirty` while dirty */
    double fat[6];       /* the fat box in the sweep: lo xyz, hi xyz */
    uint32_t group, mask, flags;
    uint32_t first_pair; /* head of its list of pairs */
    void *user;
} sbody;

/* One body's side of an excluded pair: the other body, the next record of
 * the body's list (the removal of a body drops its exclusions without a
 * walk over the table: review s29 measured 274 us a removal with 20,000
 * exclusions). */
typedef struct sexcl {
    uint32_t other, next;
} sexcl;

typedef struct spair {
    uint32_t a, b;
    uint8_t measured, contact;
    uint8_t rel_miss, rel_skip; /* the relative-pose test's failures in a row, and
                                 * how many due updates skip it still */
    uint8_t doomed;             /* in contact and dropped by the sweep this step */
    double due;
    double snap_a, snap_b;     /* the bodies' travels at the last query */
    double gap;                /* distance - report - eps at the last query */
    uint32_t next[2], prev[2]; /* lists of a ([0]) and b ([1]) */
    uint32_t kind;
    px_pose pose_a, pose_b; /* the bodies' poses at the last query */
    px_scene_pair res;
    union {
        px_pair_cache convex;
        px_model_cache model;
    } cache;
    px_pair_cache root; /* model pairs: the two root hulls' (or a model's root and the polytope) */
} spair;

typedef struct sep {
    double v;
    uint32_t id; /* body << 1 | is_max */
} sep;

typedef struct shent shent;
typedef struct snear snear;

/* What became of a due pair in the step, for the step to collect without
 * reading the pair's record (which another thread may have written). */
typedef struct sdone {
    double due;
    uint8_t what;    /* U_* */
    uint8_t report;  /* within the report distance */
    uint8_t changed; /* its contact differs from the last one collected */
} sdone;

/* A pair reported by the step: its (a, b) key, to sort the reports by. */
typedef struct srep {
    uint64_t ab;
    uint32_t pair;
} srep;

/* Open addressing on 64-bit keys (a << 32 | b), linear probing, deletion by
 * backward shift (no tombstones, so the layout depends only on the set). */
typedef struct shash {
    uint64_t *key;
    uint32_t *val;
    uint32_t cap, n; /* cap: a power of two or 0 */
} shash;

struct px_scene {
    px_allocator alloc;
    double margin, report;
    /* A power of two >= the skew of every pose the scene has taken (see
     * frame_pad); skew_grew: it grew since the last step. */
    double skx;
    int skew_grew;
    size_t model_cache_bytes;
    double time;
    int stepped;
    sbody *body;
    uint32_t n_body, cap_body, cap_bep, alive, free_hint;
    sep *axis[3];
    uint32_t *ep; /* per body, 6 positions: its min and max on each axis (apart from
                   * the bodies, so that sifting touches little memory) */
    uint32_t n_ep, cap_axis[3];
    uint32_t n_tomb; /* endpoints of removed bodies still in each array (id S_TOMB) */
    spair *pair;
    uint32_t n_pair, cap_pair, free_pair, live_pairs;
    shash pairs, excluded;
    sexcl *excl; /* records of both sides of every exclusion; free ones chained by next */
    uint32_t n_excl, cap_excl, free_excl;
    shent *heap;
    uint32_t cap_heap, n_heap;
    snear *near;
    uint32_t cap_near, n_near;
    double horizon;           /* pairs due within this long wait in the near list */
    uint32_t *slot, cap_slot; /* per pair: its position in the heap or the near list
                               * (apart from the pair records: sifting touches only these) */
    uint8_t *where;           /* per pair: Q_* */
    uint32_t cap_where;
    uint32_t *dirty, n_dirty, cap_dirty;
    uint32_t *later, n_later, cap_later;
    /* merge_in's scratch: the new endpoints of one axis, the bodies merged
     * in (then the sweep's open new boxes), and per body its place in an
     * open list (top bit: merged in) */
    sep *mbuf;
    uint32_t cap_mbuf, *act, cap_act, *act_at, cap_act_at;
    uint32_t *doomed, n_doomed, cap_doomed; /* see remove_pair */
    sdone *done;                            /* per due pair of the step: what became of it */
    uint32_t cap_done;
    struct spool *pool;  /* helper threads (NULL: the step runs on the caller's) */
    srep *rep, *rep_tmp; /* rep_tmp: the radix sort's second buffer */
    uint32_t n_rep, cap_rep, cap_rep_tmp;
    px_scene_pair *out;
    uint32_t cap_out;
    px_scene_event *ev, *pending;
    uint32_t n_ev, cap_ev, n_pending, cap_pending;
    uint32_t added, chains;
    int resync; /* the sweep's pair set may lack pairs: sort and sweep anew */
    px_scene_stats stats;
    size_t bytes;
};

/* ---- memory ------------------------------------------------------------ */

/* Grows *arr (elements of `size` bytes, capacity *cap) to hold `need`. */
static int grow(px_scene *s, void **arr, uint32_t *cap, uint32_t need, size_t size) {
    if (need <= *cap) return 1;
    if (need > UINT32_MAX / 2) return 0;
    uint32_t nc = *cap ? *cap : 16;
    while (nc < need) nc *= 2;
    void *p = pxi_alloc_array(&s->alloc, nc, size);
    if (!p) return 0;
    if (*cap) memcpy(p, *arr, (size_t)*cap * size);
    pxi_free(&s->alloc, *arr, (size_t)*cap * size);
    s->bytes += (size_t)(nc - *cap) * size;
    *arr = p;
    *cap = nc;
    return 1;
}
#define GROW(s, arr, cap, need) grow((s), (void **)&(arr), &(cap), (need), sizeof *(arr))

/* ---- sorting without allocation ------------------------------------------
 * An in-place heapsort (Williams 1964): the C library's qsort may allocate
 * a buffer behind the scene's allocator. Every key sorted here is unique,
 * so stability does not matter. Elements up to 128 bytes. */

static void elem_swap(unsigned char *a, unsigned char *b, size_t size) {
    unsigned char t[128];
    memcpy(t, a, size);
    memcpy(a, b, size);
    memcpy(b, t, size);
}

static void sift_down(unsigned char *v, size_t size, size_t i, size_t n,
                      int (*cmp)(const void *, const void *)) {
    for (;;) {
        size_t k = 2 * i + 1;
        if (k >= n) return;
        if (k + 1 < n && cmp(v + (k + 1) * size, v + k * size) > 0) ++k;
        if (cmp(v + k * size, v + i * size) <= 0) return;
        elem_swap(v + k * size, v + i * size, size);
        i = k;
    }
}

static void sort(void *base, size_t n, size_t size, int (*cmp)(const void *, const void *)) {
    unsigned char *v = base;
    if (n < 2) return;
    for (size_t i = n / 2; i-- > 0;) sift_down(v, size, i, n, cmp);
    for (size_t end = n - 1; end > 0; --end) {
        elem_swap(v, v + end * size, size);
        sift_down(v, size, 0, end, cmp);
    }
}

/* ---- hash of pairs ----------------------------------------------------- */

static uint64_t pair_key(uint32_t a, uint32_t b) {
    return a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
}

static uint32_t hash_slot(uint64_t k, uint32_t cap) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    k *= 0xc4ceb9fe1a85ec53ull;
    k ^= k >> 33;
    return (uint32_t)k & (cap - 1);
}

static uint32_t hash_get(const shash *h, uint64_t k) {
    if (!h->cap) return S_NONE;
    for (uint32_t i = hash_slot(k, h->cap);; i = (i + 1) & (h->cap - 1)) {
        if (h->val[i] == S_NONE) return S_NONE;
        if (h->key[i] == k) return h->val[i];
    }
}

static int hash_put(px_scene *s, shash *h, uint64_t k, uint32_t v) {
    if (2 * (h->n + 1) > h->cap) {
        uint32_t nc = h->cap ? 2 * h->cap : 64;
        uint64_t *key = pxi_alloc_array(&s->alloc, nc, sizeof *key);
        uint32_t *val = pxi_alloc_array(&s->alloc, nc, sizeof *val);
        if (!key || !val || nc < h->cap) {
            pxi_free(&s->alloc, key, (size_t)nc * sizeof *key);
            pxi_free(&s->alloc, val, (size_t)nc * sizeof *val);
            return 0;
        }
        for (uint32_t i = 0; i < nc; ++i) val[i] = S_NONE;
        for (uint32_t i = 0; i < h->cap; ++i) {
            if (h->val[i] == S_NONE) continue;
            uint32_t j = hash_slot(h->key[i], nc);
            while (val[j] != S_NONE) j = (j + 1) & (nc - 1);
            key[j] = h->key[i];
            val[j] = h->val[i];
        }
        pxi_free(&s->alloc, h->key, (size_t)h->cap * sizeof *key);
        pxi_free(&s->alloc, h->val, (size_t)h->cap * sizeof *val);
        s->bytes += (size_t)(nc - h->cap) * (sizeof *key + sizeof *val);
        h->key = key;
        h->val = val;
        h->cap = nc;
    }
    uint32_t i = hash_slot(k, h->cap);
    while (h->val[i] != S_NONE && h->key[i] != k) i = (i + 1) & (h->cap - 1);
    if (h->val[i] == S_NONE) h->n++;
    h->key[i] = k;
    h->val[i] = v;
    return 1;
}

static void hash_del(shash *h, uint64_t k) {
    if (!h->cap) return;
    uint32_t m = h->cap - 1, i = hash_slot(k, h->cap);
    while (h->val[i] != S_NONE && h->key[i] != k) i = (i + 1) & m;
    if (h->val[i] == S_NONE) return;
    h->n--;
    /* Backward shift: pull later entries of the run into the hole when
     * their home slot does not lie strictly between the hole and them. */
    for (uint32_t j = (i + 1) & m;; j = (j + 1) & m) {
        if (h->val[j] == S_NONE) break;
        uint32_t home = hash_slot(h->key[j], h->cap);
        if (((j - home) & m) >= ((j - i) & m)) {
            h->key[i] = h->key[j];
            h->val[i] = h->val[j];
            i = j;
        }
    }
    h->val[i] = S_NONE;
}

static void hash_free(px_scene *s, shash *h) {
    pxi_free(&s->alloc, h->key, (size_t)h->cap * sizeof *h->key);
    pxi_free(&s->alloc, h->val, (size_t)h->cap * sizeof *h->val);
    memset(h, 0, sizeof *h);
}

/* ---- the queue: a heap on (due, a, b), and the near pairs ----------------
 *
 * Heap entries carry their key, so sifting touches only the heap array.
 * Pairs due within a few steps (those within the report distance are due
 * at every step) sit in a plain list instead (where = Q_NEAR), which the
 * step scans: a pair that is due again soon costs a comparison per step
 * rather than a pop and a push. */

enum { Q_NONE = 0, Q_HEAP = 1, Q_NEAR = 2 };

/* How many of the last step's intervals ahead a pair may be due and still
 * wait in the near list. */
#define S_NEAR_STEPS 4.0

struct snear {
    double due;
    uint32_t pair;
};

struct shent {
    double due;
    uint64_t ab; /* a << 32 | b: the tie-break */
    uint32_t pair;
};

static int heap_less(const shent *x, const shent *y) {
    if (x->due != y->due) return x->due < y->due;
    return x->ab < y->ab;
}

static void heap_set(px_scene *s, uint32_t i, shent e) {
    s->heap[i] = e;
    s->slot[e.pair] = i;
}

static void heap_up(px_scene *s, uint32_t i) {
    shent e = s->heap[i];
    while (i > 0 && heap_less(&e, &s->heap[(i - 1) / 2])) {
        heap_set(s, i, s->heap[(i - 1) / 2]);
        i = (i - 1) / 2;
    }
    heap_set(s, i, e);
}

static void heap_down(px_scene *s, uint32_t i) {
    shent e = s->heap[i];
    for (;;) {
        uint32_t k = 2 * i + 1;
        if (k >= s->n_heap) break;
        if (k + 1 < s->n_heap && heap_less(&s->heap[k + 1], &s->heap[k])) ++k;
        if (!heap_less(&s->heap[k], &e)) break;
        heap_set(s, i, s->heap[k]);
        i = k;
    }
    heap_set(s, i, e);
}

/* Queues pair p at its `due`: in the near list when due within the
 * horizon, else in the heap. Capacities follow the pair pool's, so this
 * never fails. */
static void enqueue_at(px_scene *s, uint32_t p, double due) {
    if (due <= s->time + s->horizon) {
        s->where[p] = Q_NEAR;
        s->slot[p] = s->n_near;
        s->near[s->n_near++] = (snear){due, p};
        return;
    }
    const spair *q = &s->pair[p];
    s->where[p] = Q_HEAP;
    heap_set(s, s->n_heap++, (shent){due, pair_key(q->a, q->b), p});
    heap_up(s, s->n_heap - 1);
}

static void enqueue(px_scene *s, uint32_t p) { enqueue_at(s, p, s->pair[p].due); }

static void dequeue(px_scene *s, uint32_t p) {
    uint32_t i = s->slot[p];
    if (s->where[p] == Q_NEAR) {
        snear last = s->near[--s->n_near];
        s->near[i] = last;
        s->slot[last.pair] = i;
    } else if (s->where[p] == Q_HEAP) {
        shent last = s->heap[--s->n_heap];
        if (i != s->n_heap) {
            heap_set(s, i, last);
            heap_up(s, i);
            heap_down(s, s->slot[last.pair]);
        }
    }
    s->where[p] = Q_NONE;
}

/* Makes a queued pair due now. */
static void make_due(px_scene *s, uint32_t p) {
    s->pair[p].due = -INFINITY;
    if (s->where[p] == Q_NEAR) s->near[s->slot[p]].due = -INFINITY;
    if (s->where[p] == Q_HEAP) {
        s->heap[s->slot[p]].due = -INFINITY;
        heap_up(s, s->slot[p]);
    }
}

/* ---- events ------------------------------------------------------------ */

static int event(px_scene *s, uint32_t a, uint32_t b, int began) {
    if (!GROW(s, s->pending, s->cap_pending, s->n_pending + 1)) return 0;
    s->pending[s->n_pending++] = (px_scene_event){a, b, (uint32_t)began, 0};
    return 1;
}

/* ---- pairs --------------------------------------------------------------- */

static int filtered(const px_scene *s, uint32_t a, uint32_t b) {
    const sbody *x = &s->body[a], *y = &s->body[b];
    if (!(x->group & y->mask) || !(y->group & x->mask)) return 1;
    return hash_get(&s->excluded, pair_key(a, b)) != S_NONE;
}

static void link_pair(px_scene *s, uint32_t p) {
    spair *q = &s->pair[p];
    for (int k = 0; k < 2; ++k) {
        sbody *b = &s->body[k ? q->b : q->a];
        q->prev[k] = S_NONE;
        q->next[k] = b->first_pair;
        if (b->first_pair != S_NONE) {
            spair *h = &s->pair[b->first_pair];
            h->prev[h->a == (k ? q->b : q->a) ? 0 : 1] = p;
        }
        b->first_pair = p;
    }
}

static void unlink_pair(px_scene *s, uint32_t p) {
    spair *q = &s->pair[p];
    for (int k = 0; k < 2; ++k) {
        uint32_t me = k ? q->b : q->a;
        if (q->prev[k] != S_NONE) {
            spair *o = &s->pair[q->prev[k]];
            o->next[o->a == me ? 0 : 1] = q->next[k];
        } else {
            s->body[me].first_pair = q->next[k];
        }
        if (q->next[k] != S_NONE) {
            spair *o = &s->pair[q->next[k]];
            o->prev[o->a == me ? 0 : 1] = q->prev[k];
        }
    }
}

/* The next pair of body `me` after pair p in its list. */
static uint32_t next_of(const px_scene *s, uint32_t p, uint32_t me) {
    const spair *q = &s->pair[p];
    return q->next[q->a == me ? 0 : 1];
}

static int add_pair(px_scene *s, uint32_t a, uint32_t b) {
    if (a > b) {
        uint32_t t = a;
        a = b;
        b = t;
    }
    if (filtered(s, a, b)) return 1;
    uint64_t k = pair_key(a, b);
    if (hash_get(&s->pairs, k) != S_NONE) return 1;
    uint32_t p;
    if (s->free_pair != S_NONE) {
        p = s->free_pair;
        s->free_pair = s->pair[p].next[0];
    } else {
        if (!GROW(s, s->pair, s->cap_pair, s->n_pair + 1)) return 0;
        if (!GROW(s, s->heap, s->cap_heap, s->cap_pair) || !GROW(s, s->near, s->cap_near, s->cap_pair) ||
            !GROW(s, s->slot, s->cap_slot, s->cap_pair) || !GROW(s, s->where, s->cap_where, s->cap_pair))
            return 0;
        p = s->n_pair++;
    }
    if (!hash_put(s, &s->pairs, k, p)) {
        s->pair[p].a = s->pair[p].b = S_NONE;
        s->pair[p].next[0] = s->free_pair;
        s->free_pair = p;
        return 0;
    }
    spair *q = &s->pair[p];
    memset(q, 0, sizeof *q);
    q->a = a;
    q->b = b;
    const sbody *x = &s->body[a], *y = &s->body[b];
    q->kind = x->convex && y->convex ? K_CONVEX
              : x->model && y->model ? K_MODEL_MODEL
              : x->model             ? K_MODEL_CONVEX
                                     : K_CONVEX_MODEL;
    if (q->kind != K_CONVEX) {
        q->cache.model.allocator = &s->alloc;
        q->cache.model.max_bytes = s->model_cache_bytes;
    }
    q->due = -INFINITY;
    link_pair(s, p);
    enqueue(s, p);
    s->live_pairs++;
    return 1;
}

static void free_pair(px_scene *s, uint32_t p, int silent) {
    spair *q = &s->pair[p];
    /* The capacity of `pending` was reserved (px_scene_step and
     * px_scene_remove_body), so this event is never lost. */
    if (q->contact && !silent) event(s, q->a, q->b, 0);
    if (q->contact && silent) { /* a began event not delivered yet (a failed step) goes too */
        for (uint32_t i = s->n_pending; i-- > 0;) {
            const px_scene_event *e = &s->pending[i];
            if (e->body_a != q->a || e->body_b != q->b) continue;
            if (e->began) {
                memmove(&s->pending[i], &s->pending[i + 1], (s->n_pending - i - 1) * sizeof *s->pending);
                s->n_pending--;
            }
            break;
        }
    }
    if (q->doomed) /* only after a failed step: take it off the list */
        for (uint32_t i = 0; i < s->n_doomed; ++i)
            if (s->doomed[i] == p) {
                s->doomed[i] = s->doomed[--s->n_doomed];
                break;
            }
    q->doomed = 0;
    hash_del(&s->pairs, pair_key(q->a, q->b));
    dequeue(s, p);
    unlink_pair(s, p);
    if (q->kind != K_CONVEX) px_model_cache_release(&q->cache.model);
    q->a = q->b = S_NONE;
    q->next[0] = s->free_pair;
    s->free_pair = p;
    s->live_pairs--;
}

/* The sweep moves one body at a time, so two bodies that move together
 * (both by far more than their boxes) can lose their pair while only one
 * has moved and get it back when the other does: a pair in contact is
 * therefore only marked here, and freed after all moves when its boxes no
 * longer overlap (its contact then ends; else it stays, with no events). */
static void remove_pair(px_scene *s, uint32_t a, uint32_t b) {
    uint32_t p = hash_get(&s->pairs, pair_key(a, b));
    if (p == S_NONE) return;
    spair *q = &s->pair[p];
    if (q->doomed) return;
    if (q->contact && s->n_doomed < s->cap_doomed) {
        q->doomed = 1;
        s->doomed[s->n_doomed++] = p;
        return;
    }
    free_pair(s, p, 0);
}

/* ---- motion bounds ----------------------------------------------------- */

/* |v| without underflow or overflow: the plain root when its square is
 * far from both ends of the range, pxi_len_safe's scaling otherwise
 * (bodies down to 2^-1000; a velocity the user gives may be near 1e308). */
static inline double len_s(px_vec3 v) {
    double l2 = pxi_dot(v, v);
    return l2 >= 0x1p-900 && l2 <= 0x1p900 ? sqrt(l2) : pxi_len_safe(v);
}

/* x >= 0 rounded up: at least the exact value of the operation that gave
 * x (rounding to nearest is off by at most half an ulp, and x eps is at
 * least one ulp of x; the smallest subnormal covers 0 and subnormals). */
static double up(double x) { return x + (x * DBL_EPSILON + 0x1p-1074); }

/* Travel since a snapshot, rounded up (0 when none). */
static double since(double travel, double snap) { return travel == snap ? 0.0 : up(travel - snap); }

/* The skew of a pose (pxi_skew, |R^T R - I|_F) bounds |R - Q| for Q the
 * nearest rotation (R = Q (I + S), S symmetric: R^T R - I = 2S + S^2, so
 * |S| <= |R^T R - I| while |S| <= 1). px_pose_check lets rows be
 * orthonormal within 1e-6 only.
 *
 * A bound on how far any point of a body of radius `radius` about `center`
 * (body frame) moved from pose p to pose q: the reference point's
 * displacement plus the chord of the rotation times the radius. The angle
 * comes from the Frobenius norm of the difference of the nearest rotations,
 * |Qq - Qp|_F = 2 sqrt 2 sin(theta/2), bounded by |Rq - Rp|_F plus `sk`,
 * the sum of both matrices' skews; the skews are added once more for the
 * points themselves. */
static double displacement(px_vec3 center, double radius, const px_pose *p, const px_pose *q, double sk) {
    int origin = center.x == 0.0 && center.y == 0.0 && center.z == 0.0;
    px_vec3 cp = origin ? p->t : pxi_xform(p, center), cq = origin ? q->t : pxi_xform(q, center);
    double f = 0.0;
    for (int i = 0; i < 9; ++i) f += (q->r[i] - p->r[i]) * (q->r[i] - p->r[i]);
    double sn = (sqrt(f) + sk) * 0.35355339059327379; /* 1 / (2 sqrt 2), rounded up */
    /* theta = 2 asin(sn) <= 2 sn / sqrt(1 - sn^2) (asin x <= x / sqrt(1 - x^2)),
     * without the libm call; capped at pi. */
    double theta = sn < 0.7071 ? 2.0 * sn / sqrt(1.0 - sn * sn) : S_PI;
    double d = len_s(pxi_sub(cq, cp)) + (theta + sk) * radius;
    /* Rounding of the points and of theta: a few ulps of the coordinates
     * (sqrt 3 max|c| >= |c|, without a square that could underflow). */
    return d * (1.0 + 16.0 * DBL_EPSILON) +
           16.0 * DBL_EPSILON * (1.7320508075688774 * (pxi_max_abs(cp) + pxi_max_abs(cq)) + radius);
}

/* The same bound by a matrix norm, for any two matrices (no rotation
 * assumed, so no skew): every point moved at most |dc| + |Rq - Rp|_2 r, and
 * |M|_2 <= min(|M|_F, sqrt(|M|_1 |M|_inf)). Tight for turns about an axis
 * of the frame, at most 15 % above the chord otherwise; cheaper than the
 * angle. Used where a looser bound costs only a query or a refit. */
static double moved_points(px_vec3 center, double radius, const px_pose *p, const px_pose *q) {
    int origin = center.x == 0.0 && center.y == 0.0 && center.z == 0.0;
    px_vec3 cp = origin ? p->t : pxi_xform(p, center), cq = origin ? q->t : pxi_xform(q, center);
    double f = 0.0, row[3] = {0, 0, 0}, col[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double m = q->r[3 * i + j] - p->r[3 * i + j];
            f += m * m;
            row[i] += fabs(m);
            col[j] += fabs(m);
        }
    double n1 = pxi_max2(col[0], pxi_max2(col[1], col[2])), ni = pxi_max2(row[0], pxi_max2(row[1], row[2]));
    double d = len_s(pxi_sub(cq, cp)) + sqrt(pxi_min2(f, n1 * ni)) * radius;
    return d * (1.0 + 16.0 * DBL_EPSILON) +
           16.0 * DBL_EPSILON * (1.7320508075688774 * (pxi_max_abs(cp) + pxi_max_abs(cq)) + radius);
}

/* ---- sweep and prune ------------------------------------------------------ */

/* The sort's total order: value, then min before max (touching boxes
 * overlap), then body id. */
static int precedes(sep x, sep y) {
    if (x.v != y.v) return x.v < y.v;
    if ((x.id & 1) != (y.id & 1)) return (x.id & 1) < (y.id & 1);
    return (x.id >> 1) < (y.id >> 1);
}

#define EP(s, b, k, m) ((s)->ep[6 * (size_t)(b) + 2 * (k) + (m)])

static int overlap_on(const px_scene *s, uint32_t a, uint32_t b, int k) {
    return EP(s, a, k, 0) < EP(s, b, k, 1) && EP(s, b, k, 0) < EP(s, a, k, 1);
}

static int overlap_others(const px_scene *s, uint32_t a, uint32_t b, int k) {
    return overlap_on(s, a, b, (k + 1) % 3) && overlap_on(s, a, b, (k + 2) % 3);
}

/* 1 when the boxes of pair q overlap on every axis (in the arrays). */
static int pair_overlaps(const px_scene *s, const spair *q) {
    return overlap_on(s, q->a, q->b, 0) && overlap_others(s, q->a, q->b, 0);
}

/* Frees the marked pairs whose boxes no longer overlap. */
static void settle_doomed(px_scene *s) {
    for (uint32_t i = 0; i < s->n_doomed; ++i) {
        uint32_t p = s->doomed[i];
        spair *q = &s->pair[p];
        q->doomed = 0;
        if (!pair_overlaps(s, q)) free_pair(s, p, 0);
    }
    s->n_doomed = 0;
}

/* A pass changed the overlap of pair (b, o): added when b's box grew over
 * o's, removed when it shrank off it (rare; kept out of the loop, whose
 * registers it would otherwise take). */
S_NOINLINE int pass_pair(px_scene *s, uint32_t b, uint32_t o, int grow) {
    if (grow) return add_pair(s, b, o);
    remove_pair(s, b, o);
    return 1;
}

/* Moves endpoint m (0: min, 1: max) of body b on axis k in direction dir
 * (-1 or +1) to its value's place, shifting the endpoints it passes (one
 * write each; b's own is written once at the end). Passing an endpoint of
 * the other kind changes that pair's overlap on this axis: the pair is
 * added when b's box grows over it (min left, max right) and the boxes
 * overlap on the other two axes, removed when it shrinks off it. Inlined
 * with k, m and dir constant (sift): the loop is most of the sweep's cost. */
S_INLINE int move_ep(px_scene *s, uint32_t b, const int k, const int m, const int dir) {
    sep *e = s->axis[k];
    uint32_t *ep = s->ep;
    const uint32_t n = s->n_ep;
    const int grow = (m == 0) == (dir < 0);
    /* The other two axes' slots of b's endpoints: a pair overlaps there
     * when each min precedes the other's max. */
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const uint32_t *eb = &ep[6 * (size_t)b];
    uint32_t i = eb[2 * k + m];
    const sep me = e[i];
#define S_STAYS(i) (dir < 0 ? (i) == 0 || !precedes(me, e[(i)-1]) : (i) + 1 >= n || !precedes(e[(i) + 1], me))
    if (S_STAYS(i)) return 1; /* most of the four moves of a refit */
    const uint32_t b1lo = eb[2 * k1], b1hi = eb[2 * k1 + 1], b2lo = eb[2 * k2], b2hi = eb[2 * k2 + 1];
    int ok = 1;
    uint32_t start = i;
    for (;;) {
        uint32_t j = dir < 0 ? i - 1 : i + 1;
        sep o = e[j];
        uint32_t *eo = &ep[3 * (size_t)(o.id & ~1u)]; /* 6 * body */
        /* Evaluated without branches (whether o is of the other kind, and
         * overlaps on the other axes, is a coin toss at every pass): only
         * the rare change of a pair branches. */
        int change = ((o.id & 1) != (uint32_t)m) & (b1lo < eo[2 * k1 + 1]) & (eo[2 * k1] < b1hi) &
                     (b2lo < eo[2 * k2 + 1]) & (eo[2 * k2] < b2hi);
        if (change) ok &= pass_pair(s, b, o.id >> 1, grow);
        e[i] = o;
        eo[2 * k + (o.id & 1)] = i;
        i = j;
        if (S_STAYS(i)) break;
    }
#undef S_STAYS
    e[i] = me;
    ep[6 * (size_t)b + 2 * k + m] = i;
    s->stats.swaps += dir < 0 ? start - i : i - start;
    return ok;
}

/* Moves body b's endpoints on axis k to their new values' places, adding
 * and removing pairs as min/max swaps change their overlap (expanding moves
 * first, as btAxisSweep3 does, so a min never passes its own max). A pair
 * can only be present when the boxes overlap on the other two axes: the
 * removals test that before looking the pair up (Bullet's
 * USE_OVERLAP_TEST_ON_REMOVES). */
S_INLINE int sift_on(px_scene *s, uint32_t b, const int k) {
    int ok = move_ep(s, b, k, 0, -1);
    ok &= move_ep(s, b, k, 1, +1);
    ok &= move_ep(s, b, k, 0, +1);
    ok &= move_ep(s, b, k, 1, -1);
    return ok;
}

static int sift(px_scene *s, uint32_t b, int k) {
    return k == 0 ? sift_on(s, b, 0) : k == 1 ? sift_on(s, b, 1) : sift_on(s, b, 2);
}

/* The sweep's frame: the world turned 0.7 rad about y, then 0.6 rad about
 * z (REFERENCES §4.2). Bodies resting on a floor or a wall parallel to a
 * world axis would all overlap along that axis and cost a swap each per
 * move; in a generic frame no plane of the scene is parallel to an axis.
 * Distances do not depend on the frame, so boxes grown by half the report
 * distance overlap for every pair within it, in this frame as in any. */
static const double SWEEP[9] = {
    0.6312514969513067,  -0.5646424733950354,
    0.5316958010320105, /* row x: (Rz(0.6) Ry(0.7)) */
    0.43186238438518243, 0.8253356149096783,
    0.36375266832671915, /* row y */
    -0.644217687237691,  0.0,
    0.7648421872844885 /* row z */
};

/* Poses whose matrix is a little off a rotation (px_pose_check allows
 * 1e-6): px_distance measures in B's frame through R_B^T, which is not
 * R_B's inverse, and a model query may measure in either body's frame.
 * With R^T R = I + E, |E| <= k (the scene's skx), a distance D between
 * the posed bodies in the world and the same distance D_f measured in body
 * f's frame differ by at most k D + k |y| (y: body-frame points of f, |y| <=
 * reach; derivation in docs/scene.md). Every world-frame lower bound of the
 * scene (spheres, boxes, the gap a pair is keyed by) is lowered by this
 * much for both bodies, so that no pair px_distance puts within the report
 * distance is skipped. Exact rotations give k = 2^-40: a pad of ~1e-12 of
 * the bodies' reach. */
static double frame_pad(const px_scene *s, const sbody *b) { return 2.0 * s->skx * (b->reach + s->report); }

/* A world-frame lower bound d made good for the distance in either body's
 * frame, `pads` being the two bodies' frame_pad (or more). */
static double frame_lower(const px_scene *s, double d, double pads) {
    return d - 4.0 * s->skx * fabs(d) - pads;
}

static double frame_low(const px_scene *s, const sbody *x, const sbody *y, double d) {
    return frame_lower(s, d, frame_pad(s, x) + frame_pad(s, y));
}

/* Takes the skew of a pose the scene takes on: the allowance grows to the
 * next power of two (at most ~22 times: px_pose_check caps the skew). */
static void note_skew(px_scene *s, double sk) {
    if (!(sk > s->skx)) return;
    while (s->skx < sk) s->skx *= 2.0;
    s->skew_grew = 1;
}

/* The radius of the body's bounding sphere under its pose: the matrix may
 * stretch by up to 1 + its skew (|R|_2 <= 1 + |S|, R = Q (I + S)). */
static double sphere_r(const sbody *b) { return b->sr * (1.0 + b->sk); }

/* The box of the body's bounding sphere in the sweep's frame at its pose
 * (the sphere does not grow with the rotation). */
static void sphere_box(const sbody *b, double out[6]) {
    px_vec3 ws = pxi_rot(SWEEP, pxi_xform(&b->pose, b->sc));
    double ws3[3] = {ws.x, ws.y, ws.z};
    for (int i = 0; i < 3; ++i) {
        /* Rounding of the centre and the frame (its rows are unit within a
         * few ulps): a few ulps of the coordinates. */
        double es = sphere_r(b) + 16.0 * DBL_EPSILON * (fabs(ws3[i]) + b->sr);
        out[i] = ws3[i] - es;
        out[3 + i] = ws3[i] + es;
    }
}

/* The body's box in the sweep's frame at its pose: the body-frame box
 * turned (|R| half) cut down to the box of its bounding sphere (a round
 * body's turned box is up to sqrt 3 times wider). */
static void world_box(const sbody *b, double out[6]) {
    px_vec3 c = pxi_scale(pxi_add(b->lo, b->hi), 0.5), h = pxi_scale(pxi_sub(b->hi, b->lo), 0.5);
    px_vec3 wc = pxi_rot(SWEEP, pxi_xform(&b->pose, c));
    double r[9]; /* SWEEP * R */
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[3 * i + j] = SWEEP[3 * i] * b->pose.r[j] + SWEEP[3 * i + 1] * b->pose.r[3 + j] +
                           SWEEP[3 * i + 2] * b->pose.r[6 + j];
    double wc3[3] = {wc.x, wc.y, wc.z};
    sphere_box(b, out);
    for (int i = 0; i < 3; ++i) {
        double e = fabs(r[3 * i]) * h.x + fabs(r[3 * i + 1]) * h.y + fabs(r[3 * i + 2]) * h.z;
        e += 16.0 * DBL_EPSILON * (fabs(wc3[i]) + e);
        out[i] = pxi_max2(wc3[i] - e, out[i]);
        out[3 + i] = pxi_min2(wc3[i] + e, out[3 + i]);
    }
}

/* The least clearance between box w grown by g and the fat box (negative
 * when it sticks out), less the rounding of the differences. */
static double room(const double fat[6], const double w[6], double g) {
    double r = INFINITY;
    for (int i = 0; i < 3; ++i) {
        double lo = (w[i] - g) - fat[i], hi = fat[3 + i] - (w[3 + i] + g);
        double e = 4.0 * DBL_EPSILON * (fabs(w[i]) + fabs(w[3 + i]) + fabs(fat[i]) + fabs(fat[3 + i]) + g);
        r = pxi_min2(r, pxi_min2(lo, hi) - e);
    }
    return r;
}

/* 1 when fat boxes x and y overlap or touch. */
static int boxes_meet(const double x[6], const double y[6]) {
    for (int k = 0; k < 3; ++k)
        if (x[k] > y[3 + k] || y[k] > x[3 + k]) return 0;
    return 1;
}

/* New fat box when the grown world box leaves the old one; 1 when moved,
 * 2 when the new box misses the old one (a teleport).
 * Each check records the room left between the grown box and the fat box:
 * until the body's travel since then uses that room up, no point of it can
 * have left, and no box is computed. */
static int refit(px_scene *s, sbody *b) {
    if (b->fitted && since(b->travel, b->fit_travel) <= b->fit_room) return 0;
    /* Grown by half the report distance, and by the frame allowance. */
    double w[6], g = 0.5 * s->report * (1.0 + 4.0 * s->skx) + frame_pad(s, b);
    if (b->fitted) {
        /* The sphere's box first: a third of the work, and for a round
         * body most often still inside the fat box. */
        sphere_box(b, w);
        double r = room(b->fat, w, g);
        if (r >= 0.0) {
            b->fit_travel = b->travel;
            b->fit_room = r;
            return 0;
        }
    }
    world_box(b, w);
    int moved = 0;
    if (!b->fitted || room(b->fat, w, g) < 0.0) {
        double slack = g + S_SLACK * b->size, fat[6];
        for (int i = 0; i < 3; ++i) {
            fat[i] = w[i] - slack;
            fat[3 + i] = w[3 + i] + slack;
        }
        moved = b->fitted && !boxes_meet(b->fat, fat) ? 2 : 1;
        memcpy(b->fat, fat, sizeof fat);
        b->fitted = 1;
    }
    b->fit_travel = b->travel;
    b->fit_room = pxi_max2(room(b->fat, w, g), 0.0);
    return moved;
}

static void write_ep(px_scene *s, uint32_t id) {
    sbody *b = &s->body[id];
    for (int k = 0; k < 3; ++k) {
        s->axis[k][EP(s, id, k, 0)].v = b->fat[k];
        s->axis[k][EP(s, id, k, 1)].v = b->fat[3 + k];
    }
}

/* Body id's fat box moved: its endpoints take the new values and every
 * axis is sorted again (also when a pair could not be added: 0 then). */
static int resort(px_scene *s, uint32_t id) {
    s->stats.box_updates++;
    write_ep(s, id);
    int ok = 1;
    for (int k = 0; k < 3; ++k) ok &= sift(s, id, k);
    return ok;
}

static int cmp_sep(const void *x, const void *y) {
    sep a = *(const sep *)x, b = *(const sep *)y;
    return precedes(a, b) ? -1 : precedes(b, a) ? 1 : 0;
}

/* act_at's mark: the body was merged in (or is being swept as new). */
#define S_MARK 0x80000000u
/* What merging bodies into the arrays costs, in endpoints passed by
 * sifting: about this many passes over the arrays (a merge and the
 * position updates on each axis, and the sweep). */
#define S_MERGE_PASSES 8

/* Adds every missing pair whose boxes overlap and of which at least one
 * body is marked (top bit of act_at) by one sweep along axis 0, with the
 * bodies whose box is open there in two lists: a marked body meets every
 * open box, an unmarked one only the marked open boxes. Axes 1 and 2 must
 * be in order. Costs one pass over the endpoints plus one test per marked
 * pair overlapping along x. */
static int sweep_marked(px_scene *s) {
    const uint32_t mark = S_MARK;
    uint32_t *lists[2] = {s->later, s->act}, count[2] = {0, 0}, *at = s->act_at;
    const sep *e = s->axis[0];
    for (uint32_t i = 0; i < s->n_ep; ++i) {
        const uint32_t b = e[i].id >> 1, m = at[b] & mark, which = m != 0;
        uint32_t *list = lists[which];
        if (e[i].id & 1) { /* b's box closes: swap the last open one into its place */
            uint32_t pos = at[b] & ~mark, last = list[--count[which]];
            list[pos] = last;
            at[last] = (at[last] & mark) | pos;
            continue;
        }
        for (uint32_t j = 0; j < count[1]; ++j)
            if (overlap_others(s, b, s->act[j], 0) && !add_pair(s, b, s->act[j])) return 0;
        if (m)
            for (uint32_t j = 0; j < count[0]; ++j)
                if (overlap_others(s, b, s->later[j], 0) && !add_pair(s, b, s->later[j])) return 0;
        at[b] = m | count[which];
        list[count[which]++] = b;
    }
    return 1;
}

/* Sorts every axis anew and adds every overlapping pair that is missing:
 * used when the pair set may lack pairs (a failed step). */
static int rebuild(px_scene *s) {
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->n_body; ++i) {
        sbody *b = &s->body[i];
        if (!b->alive) continue;
        b->added = 0;
        for (int k = 0; k < 3; ++k) {
            s->axis[k][n] = (sep){b->fat[k], i << 1};
            s->axis[k][n + 1] = (sep){b->fat[3 + k], i << 1 | 1};
        }
        s->act_at[i] = S_MARK;
        n += 2;
    }
    s->n_ep = n;
    s->n_tomb = 0;
    s->added = 0;
    for (int k = 0; k < 3; ++k) {
        sort(s->axis[k], n, sizeof(sep), cmp_sep);
        for (uint32_t i = 0; i < n; ++i) EP(s, s->axis[k][i].id >> 1, k, s->axis[k][i].id & 1) = i;
    }
    return sweep_marked(s);
}

/* Puts the k bodies ids[] (not in the arrays; their fat boxes set) into
 * the sorted arrays: per axis their endpoints are sorted apart and merged
 * in from the back, then sweep_marked adds their pairs. O(n + k log k)
 * plus the pairs, where sifting each in passes O(n) endpoints apiece
 * (review s30: adding 5,000 bodies to 20,000 took 2.2 s of sifting). ids
 * may be s->act, which the sweep reuses. */
static int merge_in(px_scene *s, const uint32_t *ids, uint32_t k) {
    const uint32_t n = s->n_ep, k2 = 2 * k;
    for (uint32_t i = 0; i < s->n_body; ++i) s->act_at[i] = 0;
    for (uint32_t i = 0; i < k; ++i) s->act_at[ids[i]] = S_MARK;
    for (int a = 0; a < 3; ++a) {
        sep *e = s->axis[a], *m = s->mbuf;
        for (uint32_t i = 0; i < k; ++i) {
            const sbody *b = &s->body[ids[i]];
            m[2 * i] = (sep){b->fat[a], ids[i] << 1};
            m[2 * i + 1] = (sep){b->fat[3 + a], ids[i] << 1 | 1};
        }
        sort(m, k2, sizeof(sep), cmp_sep);
        uint32_t i = n, j = k2, w = n + k2;
        while (j > 0) e[--w] = i > 0 && precedes(m[j - 1], e[i - 1]) ? e[--i] : m[--j];
        for (; w < n + k2; ++w) EP(s, e[w].id >> 1, a, e[w].id & 1) = w;
    }
    s->n_ep = n + k2;
    return sweep_marked(s);
}

/* After rebuild: drops every pair whose boxes no longer overlap (a pair in
 * contact through remove_pair, so that its contact ends once the moves
 * are settled). */
static void drop_stale(px_scene *s) {
    for (uint32_t p = 0; p < s->n_pair; ++p) {
        const spair *q = &s->pair[p];
        if (q->a == S_NONE || q->doomed) continue;
        if (!pair_overlaps(s, q)) remove_pair(s, q->a, q->b);
    }
}

/* drop_stale for the pairs of body id alone. */
static void drop_stale_of(px_scene *s, uint32_t id) {
    for (uint32_t p = s->body[id].first_pair, nx; p != S_NONE; p = nx) {
        nx = next_of(s, p, id);
        const spair *q = &s->pair[p];
        if (q->doomed) continue;
        if (!pair_overlaps(s, q)) remove_pair(s, q->a, q->b);
    }
}

/* Puts a newly added body into the sorted arrays: its endpoints start past
 * every other at +inf and sift down, pairs being added only on the last
 * axis, once the other two hold their values (btAxisSweep3::addHandle). */
static int insert(px_scene *s, uint32_t id) {
    sbody *b = &s->body[id];
    uint32_t n = s->n_ep;
    for (int k = 0; k < 3; ++k) {
        s->axis[k][n] = (sep){INFINITY, id << 1};
        s->axis[k][n + 1] = (sep){INFINITY, id << 1 | 1};
        EP(s, id, k, 0) = n;
        EP(s, id, k, 1) = n + 1;
    }
    s->n_ep = n + 2;
    b->added = 0;
    int ok = 1;
    for (int k = 0; k < 3; ++k) {
        s->axis[k][EP(s, id, k, 0)].v = b->fat[k];
        s->axis[k][EP(s, id, k, 1)].v = b->fat[3 + k];
        ok &= sift(s, id, k);
    }
    return ok;
}

/* Marks a removed body's endpoints as tombstones, which the next step
 * takes out of the arrays all at once (compact): removing many bodies
 * costs one pass over the arrays, not one each. */
static void entomb(px_scene *s, uint32_t id) {
    for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 2; ++m) s->axis[k][EP(s, id, k, m)].id = S_TOMB;
    s->n_tomb += 2;
}

/* Takes the tombstones out of the arrays (before anything sifts). */
static void compact(px_scene *s) {
    if (!s->n_tomb) return;
    for (int k = 0; k < 3; ++k) {
        sep *e = s->axis[k];
        uint32_t w = 0;
        for (uint32_t i = 0; i < s->n_ep; ++i) {
            if (e[i].id == S_TOMB) continue;
            e[w] = e[i];
            EP(s, e[w].id >> 1, k, e[w].id & 1) = w;
            ++w;
        }
    }
    s->n_ep -= s->n_tomb;
    s->n_tomb = 0;
}

/* Takes the k bodies ids[] out of the arrays, for merge_in to put back. */
static void take_out(px_scene *s, const uint32_t *ids, uint32_t k) {
    for (uint32_t i = 0; i < k; ++i) entomb(s, ids[i]);
    compact(s);
}

/* Endpoints body b's box minimum passes on axis 0 to reach its new value
 * from where it is (b in the arrays) or from +inf (b not in them), by
 * binary search: an estimate of sifting it, one endpoint of six. */
static uint32_t passes(const px_scene *s, uint32_t b, int in_arrays) {
    const sep *e = s->axis[0];
    const double v = s->body[b].fat[0];
    uint32_t lo = 0, hi = s->n_ep;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (e[mid].v < v)
            lo = mid + 1;
        else
            hi = mid;
    }
    uint32_t from = in_arrays ? EP(s, b, 0, 0) : s->n_ep;
    return from > lo ? from - lo : lo - from;
}

/* Whether merging bodies in (merge_in) is cheaper than sifting them, from
 * the sum of their passes: six endpoints each against S_MERGE_PASSES
 * passes over the arrays. */
static int merge_pays(const px_scene *s, uint64_t passes_sum) {
    return 6 * passes_sum > S_MERGE_PASSES * (uint64_t)s->n_ep;
}

/* ---- motion ------------------------------------------------------------ */

/* Makes all pairs of body id due now. */
static void all_due(px_scene *s, uint32_t id) {
    for (uint32_t p = s->body[id].first_pair; p != S_NONE; p = next_of(s, p, id)) make_due(s, p);
}

/* Measures a moved body: its bounds, and its chain of known velocities
 * (with acceleration bounds). `first`: the scene's first step, before which
 * poses are free. */
static void measure(px_scene *s, uint32_t id, double dt, int first) {
    sbody *b = &s->body[id];
    double d = memcmp(&b->pose, &b->last, sizeof b->pose)
                   ? displacement(b->center, b->radius, &b->last, &b->pose, b->sk_last + b->sk)
                   : 0.0;
    /* The running sum is a fast first test; it is rounded up at every step
     * so that it never falls short (when it has grown large it only stops
     * being useful: the poses are then compared directly). */
    if (d > 0.0) b->travel = up(b->travel + d);
    double allowed = first || isinf(b->speed) ? INFINITY : b->speed > 0.0 ? b->speed * dt : 0.0;
    int violated = d > allowed;
    if (b->chain) {
        /* Known speed s_prev at the last step: this step moved at most
         * s_prev dt + a dt^2 / 2, and the new speed is at most s_prev + a dt. */
        double a = b->accel;
        if (!b->vel_now || !isfinite(dt) || d > b->s_prev * dt + 0.5 * a * dt * dt ||
            b->s_now > b->s_prev + a * dt) {
            b->chain = 0;
            s->chains--;
            if (b->vel_now) violated = 1;
            all_due(s, id);
        }
    } else if (b->vel_now && b->accel > 0.0 && !isinf(b->speed)) {
        b->chain = 1;
        s->chains++;
    }
    if (b->chain) b->s_prev = b->s_now;
    b->vel_now = 0;
    if (violated) {
        s->stats.violations++;
        all_due(s, id);
    }
    b->last = b->pose;
    b->sk_last = b->sk;
}

/* Earliest time after a query the gap g can close: u t (+ a t^2 / 2). */
static double safe_time(const px_scene *s, const spair *q, double g) {
    if (g <= 0.0) return 0.0;
    const sbody *x = &s->body[q->a], *y = &s->body[q->b];
    double u = x->speed + y->speed;
    double tau = u > 0.0 ? g / u : INFINITY;
    if (x->chain || y->chain) {
        double u0 = (x->chain ? x->s_prev : x->speed) + (y->chain ? y->s_prev : y->speed);
        double a = (x->chain ? x->accel : 0.0) + (y->chain ? y->accel : 0.0);
        /* Stable root of g = u0 t + a t^2 / 2. */
        double t2 = a > 0.0 ? 2.0 * g / (u0 + sqrt(u0 * u0 + 2.0 * a * g)) : u0 > 0.0 ? g / u0 : INFINITY;
        if (t2 > tau) tau = t2;
    }
    return isnan(tau) ? 0.0 : tau;
}

/* ---- narrow phase ------------------------------------------------------ */

/* A piece of body `in` inside a closed part of model body `out`, their
 * surfaces being apart: one representative point per connected piece of
 * `in` (its first vertex for a polytope) tested against `out`'s solid, after
 * a test against its box. Only triangle trees need this: convex leaves are
 * solids to the distance query already. 0: no piece inside, 1: some, 3:
 * every piece (each connected piece lies wholly inside or wholly outside
 * when the surfaces are apart, so then all of `in` is inside). */
static int inside_solid(const sbody *in, const sbody *out) {
    const px_model *m = out->model;
    if (!m || m->pieces != PX_PIECES_TRIANGLES || m->solid_parts == 0) return 0;
    uint32_t n = in->model ? in->model->n_reps : 1, k = 0;
    for (uint32_t i = 0; i < n; ++i) {
        px_vec3 p;
        if (in->model)
            p = in->model->reps[i];
        else
            px_convex_vertex(in->convex, 0, &p);
        px_vec3 l = pxi_xform_inv(&out->pose, pxi_xform(&in->pose, p));
        if (l.x < out->lo.x || l.y < out->lo.y || l.z < out->lo.z || l.x > out->hi.x || l.y > out->hi.y ||
            l.z > out->hi.z)
            continue;
        k += pxi_model_point_inside(m, l) != 0;
    }
    return k == 0 ? 0 : k == n ? 3 : 1;
}

/* A lower bound on the distance of a model pair: between the hulls of the
 * models' roots (a polytope is its own), else between their bounding
 * spheres; may be negative. */
static double root_gap(const sbody *x, const sbody *y, px_pair_cache *cache) {
    const px_convex *hx = x->model ? x->model->nodes[0].hull : x->convex;
    const px_convex *hy = y->model ? y->model->nodes[0].hull : y->convex;
    if (hx && hy) {
        px_distance_result d;
        if (pxi_distance_checked(hx, &x->pose, hy, &y->pose, cache, &d) == PX_OK) return d.distance;
    }
    px_vec3 cx = pxi_xform(&x->pose, x->sc), cy = pxi_xform(&y->pose, y->sc);
    return len_s(pxi_sub(cx, cy)) - sphere_r(x) - sphere_r(y);
}

/* Two polytopes whose inner balls overlap intersect (the balls' test of
 * inner sphere trees: R. Weller, G. Zachmann, "Inner sphere trees for
 * proximity and penetration queries", RSS 2009): deeply overlapping pairs,
 * which would otherwise each cost a query, are answered from their poses.
 * The posed ball of radius r stays a ball of radius at least r (1 - skew)
 * about the posed centre (|R^-1| <= 1 + skew); the overlap must also beat
 * the rounding of the centres and the frames' allowance (frame_pad), so
 * that a query in either body's frame would find the solids intersecting
 * too. On success: a common point (on the segment between the centres,
 * inside both balls) in *w. */
static int inner_overlap(const px_scene *s, const sbody *x, const sbody *y, px_vec3 *w) {
    if (!(x->ir > 0.0) || !(y->ir > 0.0)) return 0;
    px_vec3 cx = pxi_xform(&x->pose, x->ic), cy = pxi_xform(&y->pose, y->ic);
    double rx = x->ir * (1.0 - x->sk), ry = y->ir * (1.0 - y->sk);
    double d = len_s(pxi_sub(cy, cx));
    double slack = 16.0 * DBL_EPSILON * (pxi_max_abs(cx) + pxi_max_abs(cy) + x->reach + y->reach) +
                   frame_pad(s, x) + frame_pad(s, y);
    if (!(d + slack < rx + ry)) return 0;
    *w = pxi_madd(cx, pxi_sub(cy, cx), rx / (rx + ry));
    return 1;
}

/* Measures pair q. Unless `exact`, a pair whose bounding spheres, or for
 * models whose root hulls, are farther apart than the report distance is
 * not measured further: that lower bound keys it (the pair is not
 * reported; a cold query or a hierarchy descent costs far more). */
static px_status query(const px_scene *s, spair *q, const sbody *x, const sbody *y, int exact,
                       uint64_t *checked, px_error *err) {
    px_scene_pair *r = &q->res;
    r->body_a = q->a;
    r->body_b = q->b;
    px_status st = PX_OK;
    r->contained = 0;
    /* Error of a distance: a few ulps of the pair's size and place. */
    const double place = x->size + y->size + pxi_max_abs(x->pose.t) + pxi_max_abs(y->pose.t);
    double lb = -INFINITY;
    if (!exact) {
        /* The bounding spheres first (a pair entering the sweep would
         * otherwise start with a cold query), then the root hulls. */
        px_vec3 cx = pxi_xform(&x->pose, x->sc), cy = pxi_xform(&y->pose, y->sc);
        lb = frame_low(s, x, y, len_s(pxi_sub(cx, cy)) - sphere_r(x) - sphere_r(y));
        if (q->kind != K_CONVEX && !(lb - 64.0 * DBL_EPSILON * (place + fabs(lb)) > s->report))
            lb = pxi_max2(lb, frame_low(s, x, y, root_gap(x, y, &q->root)));
    }
    if (lb - 64.0 * DBL_EPSILON * (place + fabs(lb)) > s->report) {
        r->distance = lb;
        r->upper_bound = INFINITY;
        r->point_a = r->point_b = pxi_v(0.0, 0.0, 0.0);
        r->leaf_a = r->leaf_b = UINT32_MAX;
    } else if (q->kind == K_CONVEX && inner_overlap(s, x, y, &r->point_a)) {
        r->distance = r->upper_bound = 0.0;
        r->point_b = r->point_a;
        r->leaf_a = r->leaf_b = 0;
    } else if (q->kind == K_CONVEX) {
        px_distance_result d;
        (*checked)++;
        st = pxi_distance_checked(x->convex, &x->pose, y->convex, &y->pose, &q->cache.convex, &d);
        if (st == PX_OK) {
            r->distance = r->upper_bound = d.distance;
            r->point_a = d.point_a;
            r->point_b = d.point_b;
            r->leaf_a = r->leaf_b = 0;
        }
    } else {
        px_model_distance_result d;
        (*checked)++;
        if (q->kind == K_MODEL_MODEL)
            st = px_model_distance(x->model, &x->pose, y->model, &y->pose, &q->cache.model, &d);
        else if (q->kind == K_MODEL_CONVEX)
            st = px_model_distance_convex(x->model, &x->pose, y->convex, &y->pose, &q->cache.model, &d);
        else
            st = px_model_distance_convex(y->model, &y->pose, x->convex, &x->pose, &q->cache.model, &d);
        if (st == PX_OK) {
            int swap = q->kind == K_CONVEX_MODEL;
            r->distance = d.distance;
            r->upper_bound = d.upper_bound;
            r->point_a = swap ? d.point_b : d.point_a;
            r->point_b = swap ? d.point_a : d.point_b;
            r->leaf_a = swap ? d.leaf_b : d.leaf_a;
            r->leaf_b = swap ? d.leaf_a : d.leaf_b;
            /* Solids: a body inside the other's closed part touches it. */
            if (d.distance > 0.0) {
                /* Bits 0 and 2 from x in y, bits 1 and 3 from y in x. */
                uint32_t xy = (uint32_t)inside_solid(x, y), yx = (uint32_t)inside_solid(y, x);
                r->contained = (xy & 1) | (yx & 1) << 1 | (xy >> 1) << 2 | (yx >> 1) << 3;
            }
            if (r->contained) r->distance = r->upper_bound = 0.0;
        }
    }
    if (st != PX_OK)
        return pxi_error(err, st, "px_scene_step: bodies %u and %u: the distance query failed (%s)", q->a,
                         q->b, px_status_string(st));
    if (!(r->distance >= 0.0) || !isfinite(r->distance))
        return pxi_error(err, PX_ERR_INTERNAL, "px_scene_step: bodies %u and %u: distance %g", q->a, q->b,
                         r->distance);
    double eps = 64.0 * DBL_EPSILON * (place + r->distance);
    q->gap = frame_low(s, x, y, r->distance) - s->report - eps;
    q->pose_a = x->pose;
    q->pose_b = y->pose;
    q->snap_a = x->travel;
    q->snap_b = y->travel;
    q->measured = 1;
    /* q->contact follows once the step collects the pair (an event when
     * it changes). */
    r->contact = r->distance <= s->margin;
    /* A model pair far apart for its size is queried rarely, and one of
     * two static bodies never again (unless the frame allowance grows): its
     * node-pair cache is given back, so that memory follows the close
     * moving pairs (an assembly check of many touching parts would
     * otherwise keep up to model_cache_bytes per pair). */
    if (q->kind != K_CONVEX && q->cache.model.memory_bytes > 0 &&
        (q->gap > 0.5 * (x->size + y->size) || (x->flags & y->flags & PX_BODY_STATIC)))
        px_model_cache_release(&q->cache.model);
    return PX_OK;
}

/* ---- due pairs ---------------------------------------------------------- */

/* What became of a due pair in the step. */
enum { U_REKEYED = 0, U_MEASURED = 1, U_FAILED = 2 };

/* Brings pair p up to date at `time` and sets its next due time: re-keyed
 * without a query while its bodies moved less than its gap since the last
 * one, measured again otherwise (not when neither body moved). Touches
 * only the pair's own record (and `checked`), so that pairs can be brought
 * up to date on several threads. */
static px_status update_pair(const px_scene *s, uint32_t p, double time, sdone *done, uint64_t *checked,
                             px_error *err) {
    spair *q = &s->pair[p];
    const sbody *x = &s->body[q->a], *y = &s->body[q->b];
    *done = (sdone){0.0, U_REKEYED, 0, 0};
    /* How far the distance may have moved since the query: the bodies'
     * travels since then (a running sum, rounded up, cheap); when that uses
     * the gap up, each body's displacement between its pose then and now
     * (the sum stops being useful once it has grown large), and the motion
     * of a's points in b's frame between the two relative poses, far
     * smaller for bodies that move together (links of one arm). Each bounds
     * the change of the distance between the poses then and now. */
    double moved = 0.0;
    if (q->measured) {
        double ma = since(x->travel, q->snap_a), mb = since(y->travel, q->snap_b);
        moved = ma + mb > 0.0 ? up(ma + mb) : 0.0;
        /* Once the travels are large against the bodies (a long run, a far
         * excursion), their rounding makes the sum coarse: compare poses. */
        if (moved >= q->gap && moved > 0.0 && x->travel + y->travel > 0x1p20 * (x->size + y->size)) {
            double m2 = 0.0;
            if (memcmp(&x->pose, &q->pose_a, sizeof x->pose))
                m2 += moved_points(x->center, x->radius, &q->pose_a, &x->pose);
            if (memcmp(&y->pose, &q->pose_b, sizeof y->pose))
                m2 += moved_points(y->center, y->radius, &q->pose_b, &y->pose);
            moved = pxi_min2(moved, m2);
        }
        /* The relative test pays for bodies that move together; for others
         * it rarely beats the sums, so after failures in a row a pair of
         * polytopes (whose query is cheap) tries it ever less often: after
         * 1, 3, 7, ... 63 due updates. Model pairs always try it. */
        if (moved >= q->gap && moved > 0.0 && q->rel_skip > 0) {
            q->rel_skip--;
        } else if (moved >= q->gap && moved > 0.0) {
            px_pose then = pxi_relative(&q->pose_a, &q->pose_b), now = pxi_relative(&x->pose, &y->pose);
            double mr = moved_points(x->center, x->radius, &then, &now) +
                        16.0 * DBL_EPSILON *
                            (pxi_max_abs(x->pose.t) + pxi_max_abs(y->pose.t) + pxi_max_abs(q->pose_a.t) +
                             pxi_max_abs(q->pose_b.t));
            if (mr < q->gap) {
                q->rel_miss = 0;
            } else {
                if (q->rel_miss < 6 && q->kind == K_CONVEX) q->rel_miss++;
                q->rel_skip = (uint8_t)((1u << q->rel_miss) - 1u);
            }
            moved = pxi_min2(moved, mr);
        }
    }
    if (q->measured && moved < q->gap) {
        q->due = done->due = time + safe_time(s, q, q->gap - moved);
        done->changed = q->res.contact != q->contact;
        return PX_OK;
    }
    /* Measured again unless neither pose changed: a pair that moved
     * together (moved 0 by the relative test) keeps its distance, but its
     * witness points move with it. */
    if (!q->measured || moved > 0.0 || memcmp(&x->pose, &q->pose_a, sizeof x->pose) ||
        memcmp(&y->pose, &q->pose_b, sizeof y->pose)) {
        px_status st = query(s, q, x, y, 0, checked, err);
        if (st != PX_OK) {
            q->due = done->due = -INFINITY;
            done->what = U_FAILED;
            return st;
        }
    }
    done->what = U_MEASURED;
    done->report = q->res.distance <= s->report;
    done->changed = q->res.contact != q->contact;
    q->due = done->due = time + safe_time(s, q, q->gap);
    return PX_OK;
}

/* Due pairs are scattered over the pair records and the bodies: with
 * thousands of bodies, each update would wait on memory for the pair, then
 * for its two bodies. The update loops ask for them ahead: the records of
 * the pair S_AHEAD updates on, the bodies of the pair half as far on (its
 * record asked for earlier). A hint only (GCC and Clang). It must be
 * inlined: GCC otherwise finds the function free of side effects and drops
 * the calls. */
#define S_AHEAD 8u

S_INLINE void prefetch_feature(const px_convex *c, px_feature f) {
    if (f.type == PX_FEATURE_VERTEX && f.index < c->nv) {
        S_PREFETCH(&c->v[f.index]);
        S_PREFETCH(&c->v_first[f.index]);
    } else if (f.type == PX_FEATURE_EDGE && f.index < c->ne) {
        S_PREFETCH(&c->e[f.index]);
        S_PREFETCH((const char *)&c->e[f.index] + 64);
    } else if (f.type == PX_FEATURE_FACE && f.index < c->nf) {
        S_PREFETCH(&c->f[f.index]);
    }
}

S_INLINE void prefetch_due(const px_scene *s, const uint32_t *items, uint32_t i, uint32_t end) {
    if (i + S_AHEAD < end) {
        const spair *q = &s->pair[items[i + S_AHEAD]];
        S_PREFETCH(q);
        S_PREFETCH((const char *)q + 64);
        S_PREFETCH(&q->res.contact);
    }
    if (i + S_AHEAD / 2 < end) {
        const spair *q = &s->pair[items[i + S_AHEAD / 2]];
        S_PREFETCH(&s->body[q->a]);
        S_PREFETCH(&s->body[q->b]);
    }
    /* A polytope pair within the report distance is measured: the headers
     * of its polytopes two updates ahead, then the features its walk
     * starts from (one ahead). */
    if (i + 2 < end) {
        const spair *q = &s->pair[items[i + 2]];
        if (q->kind == K_CONVEX && q->gap <= 0.0) {
            S_PREFETCH(s->body[q->a].convex);
            S_PREFETCH(s->body[q->b].convex);
        }
    }
    if (i + 1 < end) {
        const spair *q = &s->pair[items[i + 1]];
        if (q->kind == K_CONVEX && q->gap <= 0.0) {
            prefetch_feature(s->body[q->a].convex, q->cache.convex.feature_a);
            prefetch_feature(s->body[q->b].convex, q->cache.convex.feature_b);
        }
    }
}

/* ---- helper threads ------------------------------------------------------
 *
 * The due pairs of a step are independent: each update reads the bodies
 * and writes only its pair. They are handed out in chunks from an atomic
 * counter; the calling thread works too, and waits at the end only for the
 * helpers that took a chunk (a helper still asleep when the work runs out
 * is not waited for). Results do not depend on which thread updated which
 * pair, and the step collects them in the due list's order, so reports,
 * events and errors are the same for any number of threads. */

#define S_MAX_THREADS 64
#define S_CHUNK 8
#define S_SPIN_NS 500000L

typedef struct swork {
    struct spool *pool;
    uint64_t checked;
    uint32_t first_failed; /* lowest index of a failed update (S_NONE: none) */
    px_error err;          /* its error */
} swork;

typedef struct spool {
    px_scene *s;
    uint32_t n_helpers;
    thrd_t th[S_MAX_THREADS - 1];
    mtx_t m;
    cnd_t go;
    uint64_t gen; /* under m: bumped for each job */
    int quit;     /* under m */
    /* The job: set while no helper is in it, published by `open`. */
    const uint32_t *items;
    uint32_t n_items;
    double time;
    atomic_uint next;     /* next item to hand out */
    atomic_int open;      /* a job is running */
    atomic_uint inflight; /* helpers inside the job */
    atomic_ullong agen;   /* gen, for the helpers' spin before they sleep */
    swork work[S_MAX_THREADS];
} spool;

/* Updates due pairs from the job's counter until it runs dry. */
static void run_chunks(spool *pl, swork *w) {
    const px_scene *s = pl->s;
    for (;;) {
        uint32_t i0 = atomic_fetch_add(&pl->next, S_CHUNK);
        if (i0 >= pl->n_items) return;
        uint32_t i1 = i0 + S_CHUNK < pl->n_items ? i0 + S_CHUNK : pl->n_items;
        for (uint32_t i = i0; i < i1; ++i) {
            prefetch_due(s, pl->items, i, i1);
            px_error e;
            px_status st = update_pair(s, pl->items[i], pl->time, &s->done[i], &w->checked, &e);
            if (st != PX_OK && i < w->first_failed) {
                w->first_failed = i;
                w->err = e;
            }
        }
    }
}

static int helper_main(void *arg) {
    swork *w = arg;
    spool *pl = w->pool;
    uint64_t seen = 0;
    for (;;) {
        /* Spin up to S_SPIN_NS for the next job before sleeping: steps
         * come in quick succession, and a sleeping helper wakes late. */
        struct timespec t0, t;
        timespec_get(&t0, TIME_UTC);
        for (unsigned i = 1; atomic_load_explicit(&pl->agen, memory_order_relaxed) == seen; ++i) {
            thrd_yield();
            if (i % 16 == 0) {
                timespec_get(&t, TIME_UTC);
                if ((t.tv_sec - t0.tv_sec) * 1000000000L + (t.tv_nsec - t0.tv_nsec) > S_SPIN_NS) break;
            }
        }
        mtx_lock(&pl->m);
        while (pl->gen == seen && !pl->quit) cnd_wait(&pl->go, &pl->m);
        seen = pl->gen;
        int quit = pl->quit;
        mtx_unlock(&pl->m);
        if (quit) return 0;
        /* Enter, then look whether the job still runs: the caller closes
         * it, then waits for those inside (both sequentially consistent,
         * so either it sees this helper or this helper sees it closed). */
        atomic_fetch_add(&pl->inflight, 1u);
        if (atomic_load(&pl->open)) run_chunks(pl, w);
        atomic_fetch_sub(&pl->inflight, 1u);
    }
}

static void pool_destroy(px_allocator *a, spool *pl) {
    if (!pl) return;
    mtx_lock(&pl->m);
    pl->quit = 1;
    cnd_broadcast(&pl->go);
    mtx_unlock(&pl->m);
    for (uint32_t k = 0; k < pl->n_helpers; ++k) thrd_join(pl->th[k], NULL);
    cnd_destroy(&pl->go);
    mtx_destroy(&pl->m);
    pxi_free(a, pl, sizeof *pl);
}

/* A pool of threads - 1 helpers, or NULL when they cannot all start. */
static spool *pool_create(px_scene *s, uint32_t threads) {
    spool *pl = pxi_alloc(&s->alloc, sizeof *pl);
    if (!pl) return NULL;
    memset(pl, 0, sizeof *pl);
    pl->s = s;
    atomic_init(&pl->next, 0u);
    atomic_init(&pl->open, 0);
    atomic_init(&pl->inflight, 0u);
    atomic_init(&pl->agen, 0u);
    if (mtx_init(&pl->m, mtx_plain) != thrd_success) {
        pxi_free(&s->alloc, pl, sizeof *pl);
        return NULL;
    }
    if (cnd_init(&pl->go) != thrd_success) {
        mtx_destroy(&pl->m);
        pxi_free(&s->alloc, pl, sizeof *pl);
        return NULL;
    }
    for (uint32_t k = 0; k + 1 < threads; ++k) {
        pl->work[k + 1].pool = pl;
        if (thrd_create(&pl->th[k], helper_main, &pl->work[k + 1]) != thrd_success) {
            pool_destroy(&s->alloc, pl);
            return NULL;
        }
        pl->n_helpers++;
    }
    return pl;
}

/* Below this many due pairs the helpers are not woken (waking costs more
 * than a few updates). */
#define S_POOL_MIN 64

/* Updates the n due pairs in items[], on the pool's threads when there is
 * one and enough work; returns the first failure in the items' order. */
static px_status update_all(px_scene *s, const uint32_t *items, uint32_t n, double time, px_error *err) {
    spool *pl = s->pool;
    if (!pl || n < S_POOL_MIN) {
        uint64_t checked = 0;
        px_status first = PX_OK;
        for (uint32_t i = 0; i < n; ++i) {
            prefetch_due(s, items, i, n);
            px_error e;
            px_status st = update_pair(s, items[i], time, &s->done[i], &checked, &e);
            if (st != PX_OK && first == PX_OK) {
                first = st;
                if (err) *err = e;
            }
        }
        s->stats.pairs_checked += checked;
        return first;
    }
    pl->items = items;
    pl->n_items = n;
    pl->time = time;
    for (uint32_t k = 0; k <= pl->n_helpers; ++k) {
        pl->work[k].checked = 0;
        pl->work[k].first_failed = S_NONE;
    }
    atomic_store(&pl->next, 0u);
    atomic_store(&pl->open, 1);
    mtx_lock(&pl->m);
    pl->gen++;
    atomic_store(&pl->agen, pl->gen);
    cnd_broadcast(&pl->go);
    mtx_unlock(&pl->m);
    run_chunks(pl, &pl->work[0]);
    atomic_store(&pl->open, 0);
    while (atomic_load(&pl->inflight) != 0u) thrd_yield();
    swork *first = NULL;
    for (uint32_t k = 0; k <= pl->n_helpers; ++k) {
        s->stats.pairs_checked += pl->work[k].checked;
        if (pl->work[k].first_failed != S_NONE && (!first || pl->work[k].first_failed < first->first_failed))
            first = &pl->work[k];
    }
    if (!first) return PX_OK;
    if (err) *err = first->err;
    return first->err.code;
}

/* ---- API ----------------------------------------------------------------- */

px_scene *px_scene_create(const px_scene_options *options, px_error *err) {
    pxi_error_clear(err);
    px_scene_options o;
    memset(&o, 0, sizeof o);
    if (options) o = *options;
    for (size_t i = 0; i < sizeof o.reserved / sizeof o.reserved[0]; ++i)
        if (o.reserved[i]) {
            pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_create: options.reserved[%zu] must be 0", i);
            return NULL;
        }
    if (!isfinite(o.margin) || o.margin < 0.0) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_create: options.margin %g must be finite and >= 0",
                  o.margin);
        return NULL;
    }
    if (o.threads > S_MAX_THREADS) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_create: options.threads %u is above %d", o.threads,
                  S_MAX_THREADS);
        return NULL;
    }
    if (o.report_distance == 0.0) o.report_distance = o.margin;
    if (!isfinite(o.report_distance) || o.report_distance < o.margin) {
        pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                  "px_scene_create: options.report_distance %g must be finite and >= the margin %g",
                  o.report_distance, o.margin);
        return NULL;
    }
    px_allocator a;
    if (pxi_allocator_resolve(o.allocator, &a, err) != PX_OK) return NULL;
    px_scene *s = pxi_alloc(&a, sizeof *s);
    if (!s) {
        pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_create: out of memory");
        return NULL;
    }
    memset(s, 0, sizeof *s);
    s->alloc = a;
    s->margin = o.margin;
    s->report = o.report_distance;
    s->skx = 0x1p-40;
    s->model_cache_bytes = o.model_cache_bytes ? o.model_cache_bytes : (size_t)256 << 10;
    s->time = -INFINITY;
    s->free_pair = S_NONE;
    s->free_excl = S_NONE;
    s->bytes = sizeof *s;
    if (o.threads > 1) {
        s->pool = pool_create(s, o.threads);
        if (!s->pool) {
            pxi_free(&a, s, sizeof *s);
            pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_create: could not start %u threads",
                      o.threads - 1);
            return NULL;
        }
        s->bytes += sizeof *s->pool;
    }
    return s;
}

void px_scene_destroy(px_scene *s) {
    if (!s) return;
    for (uint32_t p = 0; p < s->n_pair; ++p)
        if (s->pair[p].a != S_NONE && s->pair[p].kind != K_CONVEX)
            px_model_cache_release(&s->pair[p].cache.model);
    px_allocator a = s->alloc;
    pool_destroy(&a, s->pool);
    pxi_free(&a, s->body, (size_t)s->cap_body * sizeof *s->body);
    pxi_free(&a, s->ep, (size_t)s->cap_bep * sizeof *s->ep);
    for (int k = 0; k < 3; ++k) pxi_free(&a, s->axis[k], (size_t)s->cap_axis[k] * sizeof(sep));
    pxi_free(&a, s->pair, (size_t)s->cap_pair * sizeof *s->pair);
    hash_free(s, &s->pairs);
    hash_free(s, &s->excluded);
    pxi_free(&a, s->excl, (size_t)s->cap_excl * sizeof *s->excl);
    pxi_free(&a, s->heap, (size_t)s->cap_heap * sizeof *s->heap);
    pxi_free(&a, s->near, (size_t)s->cap_near * sizeof *s->near);
    pxi_free(&a, s->slot, (size_t)s->cap_slot * sizeof *s->slot);
    pxi_free(&a, s->where, (size_t)s->cap_where * sizeof *s->where);
    pxi_free(&a, s->dirty, (size_t)s->cap_dirty * sizeof *s->dirty);
    pxi_free(&a, s->later, (size_t)s->cap_later * sizeof *s->later);
    pxi_free(&a, s->mbuf, (size_t)s->cap_mbuf * sizeof *s->mbuf);
    pxi_free(&a, s->act, (size_t)s->cap_act * sizeof *s->act);
    pxi_free(&a, s->act_at, (size_t)s->cap_act_at * sizeof *s->act_at);
    pxi_free(&a, s->done, (size_t)s->cap_done * sizeof *s->done);
    pxi_free(&a, s->doomed, (size_t)s->cap_doomed * sizeof *s->doomed);
    pxi_free(&a, s->rep, (size_t)s->cap_rep * sizeof *s->rep);
    pxi_free(&a, s->rep_tmp, (size_t)s->cap_rep_tmp * sizeof *s->rep_tmp);
    pxi_free(&a, s->out, (size_t)s->cap_out * sizeof *s->out);
    pxi_free(&a, s->ev, (size_t)s->cap_ev * sizeof *s->ev);
    pxi_free(&a, s->pending, (size_t)s->cap_pending * sizeof *s->pending);
    pxi_free(&a, s, sizeof *s);
}

static int body_ok(const px_scene *s, uint32_t id) { return s && id < s->n_body && s->body[id].alive; }

int pxi_scene_body_movable(const px_scene *s, uint32_t id) {
    return body_ok(s, id) && !(s->body[id].flags & PX_BODY_STATIC);
}

/* The pose's translation must stay where differences of coordinates are
 * exact enough and finite (the queries' range). */
/* `what` names the call and the body ("px_scene_set_pose: body 3"). */
static px_status check_pose(const px_pose *pose, const char *what, px_error *err) {
    if (!pose) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "%s: pose is NULL", what);
    px_error why;
    px_status st = px_pose_check(pose, &why);
    if (st != PX_OK) return pxi_error(err, st, "%s: %s", what, why.message);
    if (!(pxi_max_abs(pose->t) <= 0x1p250))
        return pxi_error(err, PX_ERR_RANGE, "%s: the pose's translation is beyond 2^250", what);
    return PX_OK;
}

/* Rejects NaN (tested first: an ordered comparison with NaN raises
 * FE_INVALID) and negatives, allows INFINITY. */
static int bound_ok(double v) { return !isnan(v) && v >= 0.0; }

px_status px_scene_add_body(px_scene *s, const px_body_desc *d, uint32_t *id, px_error *err) {
    pxi_error_clear(err);
    if (!s || !d || !id) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_add_body: NULL argument");
    if (!d->model == !d->convex)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_scene_add_body: exactly one of desc.model and desc.convex must be set");
    if (d->flags & ~(uint32_t)PX_BODY_STATIC)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_add_body: unknown flags 0x%x", d->flags);
    for (int i = 0; i < 3; ++i)
        if (d->reserved[i])
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_add_body: desc.reserved[%d] must be 0",
                             i);
    if (!bound_ok(d->max_speed) || !bound_ok(d->max_angular_speed) || !bound_ok(d->max_accel) ||
        !bound_ok(d->max_angular_accel) || isinf(d->max_accel) || isinf(d->max_angular_accel))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_scene_add_body: motion bounds must be >= 0 (speeds may be INFINITY, "
                         "accelerations must be finite)");
    if (!pxi_is_finite3(d->center))
        return pxi_error(err, PX_ERR_NON_FINITE, "px_scene_add_body: desc.center is not finite");
    if (!(pxi_max_abs(d->center) <= 0x1p250))
        return pxi_error(err, PX_ERR_RANGE, "px_scene_add_body: desc.center is beyond 2^250");
    px_status st = check_pose(&d->pose, "px_scene_add_body", err);
    if (st != PX_OK) return st;
    /* Body-frame box. */
    px_vec3 lo, hi;
    if (d->model) {
        px_model_info info;
        st = px_model_get_info(d->model, &info);
        if (st != PX_OK) return pxi_error(err, st, "px_scene_add_body: the model is not valid");
        lo = info.min;
        hi = info.max;
    } else {
        uint32_t nv = px_convex_vertex_count(d->convex);
        if (nv == 0)
            return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_add_body: the polytope is empty");
        px_convex_vertex(d->convex, 0, &lo);
        hi = lo;
        for (uint32_t i = 1; i < nv; ++i) {
            px_vec3 p;
            px_convex_vertex(d->convex, i, &p);
            lo = pxi_v(pxi_min2(lo.x, p.x), pxi_min2(lo.y, p.y), pxi_min2(lo.z, p.z));
            hi = pxi_v(pxi_max2(hi.x, p.x), pxi_max2(hi.y, p.y), pxi_max2(hi.z, p.z));
        }
    }
    /* The smallest free id, for determinism (no id below the hint is free). */
    uint32_t i = s->free_hint;
    while (i < s->n_body && s->body[i].alive) ++i;
    /* Every array grows first; the scene changes only once all did. */
    const int fresh = i == s->n_body;
    if (fresh && (s->n_body >= (UINT32_MAX >> 3) || !GROW(s, s->body, s->cap_body, s->n_body + 1) ||
                  !grow(s, (void **)&s->ep, &s->cap_bep, 6 * (s->n_body + 1), sizeof *s->ep)))
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_add_body: out of memory");
    for (int k = 0; k < 3; ++k)
        if (!grow(s, (void **)&s->axis[k], &s->cap_axis[k], 2 * (s->alive + 1), sizeof(sep)))
            return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_add_body: out of memory");
    if (!GROW(s, s->dirty, s->cap_dirty, s->alive + 1) || !GROW(s, s->later, s->cap_later, s->alive + 1) ||
        !GROW(s, s->mbuf, s->cap_mbuf, 2 * (s->alive + 1)) || !GROW(s, s->act, s->cap_act, s->alive + 1) ||
        !GROW(s, s->act_at, s->cap_act_at, s->n_body + 1))
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_add_body: out of memory");
    if (fresh) s->n_body++;
    sbody *b = &s->body[i];
    memset(b, 0, sizeof *b);
    b->model = d->model;
    b->convex = d->convex;
    b->pose = b->last = d->pose;
    b->sk = b->sk_last = pxi_skew(d->pose.r);
    note_skew(s, b->sk);
    b->center = d->center;
    b->lo = lo;
    b->hi = hi;
    b->size = 0.5 * len_s(pxi_sub(hi, lo));
    double r = 0.0;
    for (int c = 0; c < 8; ++c) {
        px_vec3 p = pxi_v(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
        r = pxi_max2(r, len_s(pxi_sub(p, d->center)));
    }
    /* The bounding sphere (the model's root, the polytope's) often bounds
     * the radius about `center` tighter than the box's corners. */
    px_vec3 sc;
    double sr;
    if (d->model) {
        sc = d->model->nodes[0].center;
        sr = d->model->nodes[0].radius;
    } else {
        px_bounds bd;
        px_convex_bounds(d->convex, NULL, &bd);
        sc = bd.center;
        sr = bd.radius;
    }
    r = pxi_min2(r, len_s(pxi_sub(sc, d->center)) + sr);
    b->radius = r * (1.0 + 8.0 * DBL_EPSILON);
    b->sc = sc;
    b->sr = sr * (1.0 + 8.0 * DBL_EPSILON);
    if (d->convex && d->convex->inner_radius > 0.0) {
        b->ic = pxi_add(d->convex->inner_center, d->convex->origin);
        b->ir = d->convex->inner_radius;
    }
    b->reach = len_s(sc) + 3.0 * b->sr;
    int fixed = (d->flags & PX_BODY_STATIC) != 0;
    b->vmax = fixed ? 0.0 : d->max_speed;
    b->wmax = fixed ? 0.0 : d->max_angular_speed;
    b->speed = b->wmax > 0.0 && b->radius > 0.0 ? b->vmax + b->wmax * b->radius : b->vmax;
    b->accel = fixed ? 0.0 : d->max_accel + (b->radius > 0.0 ? d->max_angular_accel * b->radius : 0.0);
    b->group = d->group ? d->group : UINT32_MAX;
    b->mask = d->mask ? d->mask : UINT32_MAX;
    b->flags = d->flags;
    b->first_pair = S_NONE;
    b->first_excl = S_NONE;
    b->user = d->user;
    b->alive = 1;
    b->added = 1;
    for (int k = 0; k < 3; ++k) b->fat[k] = INFINITY, b->fat[3 + k] = -INFINITY;
    b->fitted = 0;
    refit(s, b);
    s->alive++;
    s->added++;
    s->free_hint = i + 1;
    *id = i;
    return PX_OK;
}

px_status px_scene_remove_body(px_scene *s, uint32_t id, px_error *err) {
    pxi_error_clear(err);
    if (!body_ok(s, id))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_remove_body: no body %u in the scene", id);
    sbody *b = &s->body[id];
    /* Room for its contacts' ended events, before anything changes (a body
     * without pairs has none: its removal never fails). */
    if (b->first_pair != S_NONE && !GROW(s, s->pending, s->cap_pending, s->n_pending + s->live_pairs + 1))
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_remove_body: out of memory");
    while (b->first_pair != S_NONE) free_pair(s, b->first_pair, 0);
    if (!b->added)
        entomb(s, id);
    else
        s->added--;
    if (b->chain) s->chains--;
    /* Exclusions name ids, which will be reused. */
    for (uint32_t r = b->first_excl; r != S_NONE;) {
        const uint32_t o = s->excl[r].other, next = s->excl[r].next;
        hash_del(&s->excluded, pair_key(id, o));
        for (uint32_t *at = &s->body[o].first_excl; *at != S_NONE; at = &s->excl[*at].next)
            if (s->excl[*at].other == id) {
                const uint32_t q = *at;
                *at = s->excl[q].next;
                s->excl[q].next = s->free_excl;
                s->free_excl = q;
                break;
            }
        s->excl[r].next = s->free_excl;
        s->free_excl = r;
        r = next;
    }
    b->first_excl = S_NONE;
    if (b->dirty) {
        const uint32_t last = s->dirty[--s->n_dirty];
        s->dirty[b->dirty_at] = last;
        s->body[last].dirty_at = b->dirty_at;
        b->dirty = 0;
    }
    b->alive = 0;
    s->alive--;
    if (id < s->free_hint) s->free_hint = id;
    return PX_OK;
}

void *px_scene_body_user(const px_scene *s, uint32_t id) { return body_ok(s, id) ? s->body[id].user : NULL; }

px_status px_scene_exclude_pair(px_scene *s, uint32_t a, uint32_t b, px_error *err) {
    pxi_error_clear(err);
    if (!body_ok(s, a) || !body_ok(s, b) || a == b)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_scene_exclude_pair: bodies %u and %u are not two bodies of the scene", a, b);
    if (hash_get(&s->excluded, pair_key(a, b)) == S_NONE) {
        /* Two records (from the free list, or new), then the table entry. */
        uint32_t r[2];
        for (int k = 0; k < 2; ++k) {
            if (s->free_excl != S_NONE) {
                r[k] = s->free_excl;
                s->free_excl = s->excl[r[k]].next;
            } else if (GROW(s, s->excl, s->cap_excl, s->n_excl + 1)) {
                r[k] = s->n_excl++;
            } else {
                r[k] = S_NONE;
            }
        }
        if (r[0] == S_NONE || r[1] == S_NONE || !hash_put(s, &s->excluded, pair_key(a, b), 0)) {
            for (int k = 0; k < 2; ++k)
                if (r[k] != S_NONE) {
                    s->excl[r[k]].next = s->free_excl;
                    s->free_excl = r[k];
                }
            return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_exclude_pair: out of memory");
        }
        s->excl[r[0]] = (sexcl){b, s->body[a].first_excl};
        s->body[a].first_excl = r[0];
        s->excl[r[1]] = (sexcl){a, s->body[b].first_excl};
        s->body[b].first_excl = r[1];
    }
    uint32_t p = hash_get(&s->pairs, pair_key(a, b));
    if (p != S_NONE) free_pair(s, p, 1);
    return PX_OK;
}

static px_status mark_dirty(px_scene *s, uint32_t id) {
    sbody *b = &s->body[id];
    if (!b->dirty) {
        b->dirty = 1;
        b->dirty_at = s->n_dirty;
        s->dirty[s->n_dirty++] = id; /* capacity: one per body */
    }
    return PX_OK;
}

/* check_pose's test and the skew in one pass, for the pose set at every
 * step (pxi_pose_ok_skew) plus the translation's range; 0 when any fails
 * (check_pose then says which). */
static int pose_fast(const px_pose *pose, double *sk) {
    return pxi_pose_ok_skew(pose, sk) && pxi_max_abs(pose->t) <= 0x1p250;
}

px_status px_scene_set_pose(px_scene *s, uint32_t id, const px_pose *pose, px_error *err) {
    if (!body_ok(s, id))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_set_pose: no body %u in the scene", id);
    if (s->body[id].flags & PX_BODY_STATIC)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_set_pose: body %u is static", id);
    double sk;
    if (!pose || !pose_fast(pose, &sk)) {
        char what[48];
        snprintf(what, sizeof what, "px_scene_set_pose: body %u", id);
        px_status st = check_pose(pose, what, err);
        /* Not reached: pose_fast refuses only what check_pose refuses. */
        if (st == PX_OK) st = pxi_error(err, PX_ERR_INTERNAL, "px_scene_set_pose: pose test mismatch");
        return st;
    }
    pxi_error_clear(err);
    s->body[id].pose = *pose;
    s->body[id].sk = sk;
    note_skew(s, sk);
    return mark_dirty(s, id);
}

px_status px_scene_set_velocity(px_scene *s, uint32_t id, px_vec3 v, double w, px_error *err) {
    if (!body_ok(s, id))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_set_velocity: no body %u in the scene", id);
    if (s->body[id].flags & PX_BODY_STATIC)
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_set_velocity: body %u is static", id);
    sbody *b = &s->body[id];
    double lin = len_s(v);
    if (!pxi_is_finite3(v) || !isfinite(w) || w < 0.0 || lin > b->vmax || w > b->wmax)
        return pxi_error(
            err, PX_ERR_INVALID_ARGUMENT,
            "px_scene_set_velocity: body %u: speed %g and angular speed %g must be finite and within "
            "its bounds %g and %g",
            id, lin, w, b->vmax, b->wmax);
    pxi_error_clear(err);
    b->s_now = lin + w * b->radius;
    b->vel_now = 1;
    return mark_dirty(s, id);
}

/* Sorts the step's reports by (a, b), keys being unique: a radix sort
 * (least significant digit first, 11 bits a digit) over a key of 2 w bits,
 * a << w | b for ids below 2^w; a few thousand reports sort in two or three
 * passes over them, where the heapsort took 20 compares each. */
static void sort_reports(px_scene *s) {
    uint32_t n = s->n_rep, w = 1;
    if (n < 2) return;
    while (w < 32 && (s->n_body - 1) >> w) ++w;
    srep *src = s->rep, *dst = s->rep_tmp;
    for (uint32_t i = 0; i < n; ++i) src[i].ab = (src[i].ab >> 32) << w | (src[i].ab & 0xffffffffu);
    uint32_t count[2048];
    for (uint32_t shift = 0; shift < 2 * w; shift += 11) {
        memset(count, 0, sizeof count);
        for (uint32_t i = 0; i < n; ++i) count[(src[i].ab >> shift) & 2047u]++;
        for (uint32_t d = 0, sum = 0; d < 2048; ++d) {
            uint32_t c = count[d];
            count[d] = sum;
            sum += c;
        }
        for (uint32_t i = 0; i < n; ++i) dst[count[(src[i].ab >> shift) & 2047u]++] = src[i];
        srep *t = src;
        src = dst;
        dst = t;
    }
    /* The keys back, into s->rep. */
    for (uint32_t i = 0; i < n; ++i)
        s->rep[i] = (srep){(src[i].ab >> w) << 32 | (src[i].ab & ((1ull << w) - 1)), src[i].pair};
}

static int cmp_event(const void *x, const void *y) {
    const px_scene_event *a = x, *b = y;
    if (a->body_a != b->body_a) return a->body_a < b->body_a ? -1 : 1;
    if (a->body_b != b->body_b) return a->body_b < b->body_b ? -1 : 1;
    /* One pair's events (ended, then began again after a body was removed
     * and its id reused) keep their order: `reserved` tags the sequence. */
    return a->reserved < b->reserved ? -1 : a->reserved > b->reserved;
}

px_status px_scene_step(px_scene *s, double time, px_error *err) {
    pxi_error_clear(err);
    if (!s) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_step: scene is NULL");
    if (!isfinite(time) || (s->stepped && time < s->time))
        return pxi_error(err, PX_ERR_INVALID_ARGUMENT,
                         "px_scene_step: time %g is not finite or goes back (last %g)", time, s->time);
    /* The last step's reports and events are gone from here on, also when
     * this step fails (its events then wait for the next one). */
    s->n_rep = 0;
    s->n_ev = 0;
    /* Room for every contact that may end in this step (pairs the sweep
     * drops, see remove_pair), reserved before anything changes. */
    if (!GROW(s, s->pending, s->cap_pending, s->n_pending + s->live_pairs + 1) ||
        !GROW(s, s->doomed, s->cap_doomed, s->live_pairs + 1))
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_step: out of memory");
    compact(s);
    double dt = s->stepped ? time - s->time : INFINITY;
    uint64_t checked0 = 0;
    s->stats.swaps = 0;
    s->stats.violations = 0;
    s->stats.pairs_checked = checked0;
    s->stats.pairs_due = 0;
    s->stats.moved = s->n_dirty;
    s->stats.box_updates = 0;
    /* Bodies whose velocity chain lapses without a pose or velocity set. */
    if (s->chains)
        for (uint32_t i = 0; i < s->n_body; ++i)
            if (s->body[i].alive && s->body[i].chain && !s->body[i].dirty) mark_dirty(s, i);
    int ok = 1;
    /* The bodies whose fat box moved are kept at the front of `dirty`;
     * those whose new box misses the old one are also listed in `act`. */
    uint32_t n_moved = 0, far = 0;
    for (uint32_t i = 0; i < s->n_dirty; ++i) {
        uint32_t id = s->dirty[i];
        sbody *b = &s->body[id];
        b->dirty = 0;
        /* A body added since the last step has no pairs yet: its first
         * move is free, as every body's before the first step. */
        measure(s, id, dt, !s->stepped || b->added);
        /* A body added since the last step is sorted in below, at its
         * refitted box. */
        int moved = refit(s, b);
        if (moved && !b->added) {
            s->dirty[n_moved++] = id;
            if (moved == 2) s->act[far++] = id;
        }
    }
    s->n_dirty = 0;
    /* Bodies whose new box misses the old one (teleports) pass O(n)
     * endpoints apiece when sifted: when a binary search apiece says they
     * would pass more than a few merges cost, they are taken out of the
     * arrays and merged back in, and their pairs compared with the boxes
     * (drop_stale_of) once every body is in place. */
    uint64_t cost = 0;
    for (uint32_t i = 0; i < far; ++i) cost += passes(s, s->act[i], 1);
    const int merge = far && merge_pays(s, cost);
    if (merge) {
        s->stats.box_updates += far;
        take_out(s, s->act, far);
        ok &= merge_in(s, s->act, far); /* marks them in act_at */
    }
    for (uint32_t i = 0; i < n_moved; ++i)
        if (!merge || !(s->act_at[s->dirty[i]] & S_MARK)) ok &= resort(s, s->dirty[i]);
    if (merge)
        for (uint32_t i = 0; i < n_moved; ++i)
            if (s->act_at[s->dirty[i]] & S_MARK) drop_stale_of(s, s->dirty[i]);
    /* A pose more skewed than any before widened the frame allowance
     * (frame_pad): every box is checked against it, and every pair is
     * measured anew (its gap was keyed with the old one). */
    if (s->skew_grew) {
        s->skew_grew = 0;
        for (uint32_t id = 0; id < s->n_body; ++id) {
            sbody *b = &s->body[id];
            if (!b->alive || b->added) continue;
            b->fit_room = -1.0;
            if (refit(s, b)) ok &= resort(s, id);
        }
        for (uint32_t p = 0; p < s->n_pair; ++p)
            if (s->pair[p].a != S_NONE) {
                s->pair[p].measured = 0;
                make_due(s, p);
            }
    }
    /* A pair the sweep could not add (out of memory) would be lost for
     * good: the scene then sorts everything anew and adds every missing
     * pair, now or at the next step, and reports the failure meanwhile. */
    if (!ok) s->resync = 1;
    /* Bodies added since the last step: sifted in from +inf when few and
     * cheap to sift (as estimated for teleports), else merged in. */
    if (!s->resync && s->added) {
        uint32_t k = 0;
        cost = 0;
        for (uint32_t id = 0; id < s->n_body; ++id)
            if (s->body[id].alive && s->body[id].added) {
                s->act[k++] = id;
                cost += passes(s, id, 0);
            }
        if (k > 16 || merge_pays(s, cost)) {
            for (uint32_t i = 0; i < k; ++i) s->body[s->act[i]].added = 0;
            if (!merge_in(s, s->act, k)) s->resync = 1;
        } else {
            for (uint32_t i = 0; i < k; ++i)
                if (!insert(s, s->act[i])) s->resync = 1;
        }
        s->added = 0;
    }
    if (s->resync && rebuild(s)) {
        drop_stale(s);
        s->resync = 0;
    }
    settle_doomed(s);
    /* The moved bodies were measured against `time`: it is the step's now,
     * also when the sweep failed (else the next step would measure its
     * motion against the same interval again, and pairs keyed from the
     * bounds would come due too late: review s29). */
    s->time = time;
    s->stepped = 1;
    if (s->resync) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_step: out of memory");
    /* Due pairs. */
    s->n_rep = 0;
    s->n_later = 0;
    if (!GROW(s, s->later, s->cap_later, s->live_pairs + 1) ||
        !GROW(s, s->done, s->cap_done, s->live_pairs + 1) ||
        !GROW(s, s->rep, s->cap_rep, s->live_pairs + 1) ||
        !GROW(s, s->rep_tmp, s->cap_rep_tmp, s->live_pairs + 1))
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_step: out of memory");
    /* The due pairs: the near list's (scanned from its end, so that a
     * removal, which moves the last entry into the hole, skips nothing),
     * then the heap's. All leave their queue, are brought up to date, then
     * collected in this order: reports, events, and back to the near list
     * when due again within the horizon, else to the heap. */
    s->horizon = dt > 0.0 && isfinite(dt) ? S_NEAR_STEPS * dt : 0.0;
    if (!isfinite(time + s->horizon)) s->horizon = 0.0;
    uint32_t nd = 0;
    uint32_t *due = s->later;
    const double soon = time + s->horizon;
    for (uint32_t i = s->n_near; i-- > 0;) {
        const snear e = s->near[i];
        if (e.due <= time) {
            due[nd++] = e.pair;
            dequeue(s, e.pair);
        } else if (e.due > soon) { /* queued after a longer step: back to the heap */
            dequeue(s, e.pair);
            enqueue_at(s, e.pair, e.due);
        }
    }
    while (s->n_heap > 0 && s->heap[0].due <= time) {
        due[nd++] = s->heap[0].pair;
        dequeue(s, s->heap[0].pair);
    }
    px_status st = update_all(s, due, nd, time, err);
    s->stats.pairs_due = nd;
    int oom = 0;
    for (uint32_t i = 0; i < nd; ++i) {
        uint32_t p = due[i];
        const sdone *d = &s->done[i];
        if (d->report) s->rep[s->n_rep++] = (srep){pair_key(s->pair[p].a, s->pair[p].b), p};
        if (d->changed) {
            spair *q = &s->pair[p];
            if (event(s, q->a, q->b, (int)q->res.contact)) {
                q->contact = (uint8_t)q->res.contact;
            } else {
                oom = 1; /* due again at once: measured, and its event made, next step */
                q->due = -INFINITY;
                s->done[i].due = -INFINITY;
            }
        }
        enqueue_at(s, p, s->done[i].due);
    }
    if (oom && st == PX_OK) st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_step: out of memory");
    if (st != PX_OK) {
        s->n_rep = 0;
        return st;
    }
    /* Reports, in (a, b) order. */
    if (!GROW(s, s->out, s->cap_out, s->n_rep)) {
        s->n_rep = 0;
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_step: out of memory");
    }
    sort_reports(s);
    for (uint32_t i = 0; i < s->n_rep; ++i) s->out[i] = s->pair[s->rep[i].pair].res;
    /* Events, in (a, b) order. */
    if (!GROW(s, s->ev, s->cap_ev, s->n_pending)) {
        s->n_rep = 0;
        return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_step: out of memory");
    }
    for (uint32_t i = 0; i < s->n_pending; ++i) s->pending[i].reserved = i;
    sort(s->pending, s->n_pending, sizeof *s->pending, cmp_event);
    for (uint32_t i = 0; i < s->n_pending; ++i) {
        s->ev[i] = s->pending[i];
        s->ev[i].reserved = 0;
    }
    s->n_ev = s->n_pending;
    s->n_pending = 0;
    s->stats.bodies = s->alive;
    s->stats.candidate_pairs = s->live_pairs;
    return PX_OK;
}

const px_scene_pair *px_scene_pairs(const px_scene *s, size_t *count) {
    if (count) *count = s ? s->n_rep : 0;
    return s ? s->out : NULL;
}

const px_scene_event *px_scene_events(const px_scene *s, size_t *count) {
    if (count) *count = s ? s->n_ev : 0;
    return s ? s->ev : NULL;
}

px_status px_scene_get_stats(const px_scene *s, px_scene_stats *out) {
    if (!s || !out) return PX_ERR_INVALID_ARGUMENT;
    *out = s->stats;
    out->bodies = s->alive;
    size_t bytes = s->bytes;
    for (uint32_t p = 0; p < s->n_pair; ++p)
        if (s->pair[p].a != S_NONE && s->pair[p].kind != K_CONVEX)
            bytes += s->pair[p].cache.model.memory_bytes;
    out->memory_bytes = bytes;
    return PX_OK;
}

/* ---- global minimum ------------------------------------------------------ */

typedef struct sbox {
    double b[6];
    uint32_t id;
} sbox;

static int cmp_sbox(const void *x, const void *y) {
    const sbox *a = x, *b = y;
    if (a->b[0] != b->b[0]) return a->b[0] < b->b[0] ? -1 : 1;
    return a->id < b->id ? -1 : a->id > b->id;
}

static double box_gap(const double *a, const double *b) {
    double g2 = 0.0;
    for (int i = 0; i < 3; ++i) {
        double g = pxi_max2(a[i] - b[3 + i], b[i] - a[3 + i]);
        if (g > 0.0) g2 += g * g;
    }
    return sqrt(g2);
}

px_status px_scene_min_distance(px_scene *s, px_scene_pair *out, px_error *err) {
    pxi_error_clear(err);
    if (!s || !out) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_min_distance: NULL argument");
    memset(out, 0, sizeof *out);
    out->body_a = out->body_b = UINT32_MAX;
    out->distance = out->upper_bound = INFINITY;
    if (!s->stepped) return pxi_error(err, PX_ERR_INVALID_ARGUMENT, "px_scene_min_distance: no step yet");
    /* The last step's poses (`last`) of the bodies that took part in it
     * and are still there. A reported pair is nearer than every pair not
     * reported. */
    for (uint32_t i = 0; i < s->n_rep; ++i) {
        const px_scene_pair *r = &s->out[i];
        if (r->distance < out->distance && s->body[r->body_a].alive && s->body[r->body_b].alive &&
            !s->body[r->body_a].added && !s->body[r->body_b].added && !filtered(s, r->body_a, r->body_b))
            *out = *r;
    }
    if (out->body_a != UINT32_MAX) return PX_OK;
    sbox *bx = pxi_alloc_array(&s->alloc, s->alive ? s->alive : 1, sizeof *bx);
    if (!bx) return pxi_error(err, PX_ERR_OUT_OF_MEMORY, "px_scene_min_distance: out of memory");
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->n_body; ++i) {
        if (!s->body[i].alive || s->body[i].added) continue;
        sbody last = s->body[i];
        last.pose = last.last;
        last.sk = last.sk_last;
        world_box(&last, bx[n].b);
        bx[n++].id = i;
    }
    sort(bx, n, sizeof *bx, cmp_sbox);
    /* Box gaps are world-frame bounds: lowered by the frame allowance. */
    double pad_max = 0.0;
    for (uint32_t i = 0; i < n; ++i) pad_max = pxi_max2(pad_max, frame_pad(s, &s->body[bx[i].id]));
    px_status st = PX_OK;
    spair tmp;
    for (uint32_t i = 0; i < n && st == PX_OK; ++i)
        for (uint32_t j = i + 1; j < n && st == PX_OK; ++j) {
            if (frame_lower(s, bx[j].b[0] - bx[i].b[3], 2.0 * pad_max) > out->distance) break;
            uint32_t a = bx[i].id, b = bx[j].id;
            if (a > b) a = bx[j].id, b = bx[i].id;
            if (filtered(s, a, b) ||
                frame_low(s, &s->body[a], &s->body[b], box_gap(bx[i].b, bx[j].b)) > out->distance)
                continue;
            memset(&tmp, 0, sizeof tmp);
            tmp.a = a;
            tmp.b = b;
            sbody x0 = s->body[a], y0 = s->body[b];
            x0.pose = x0.last;
            y0.pose = y0.last;
            x0.sk = x0.sk_last;
            y0.sk = y0.sk_last;
            const sbody *x = &x0, *y = &y0;
            tmp.kind = x->convex && y->convex ? K_CONVEX
                       : x->model && y->model ? K_MODEL_MODEL
                       : x->model             ? K_MODEL_CONVEX
                                              : K_CONVEX_MODEL;
            if (tmp.kind != K_CONVEX) {
                tmp.cache.model.allocator = &s->alloc;
                tmp.cache.model.max_bytes = s->model_cache_bytes;
            }
            uint64_t checked = 0; /* the minimum's queries are not the step's */
            st = query(s, &tmp, x, y, 1, &checked, err);
            if (tmp.kind != K_CONVEX) px_model_cache_release(&tmp.cache.model);
            if (st == PX_OK && tmp.res.distance < out->distance) *out = tmp.res;
        }
    pxi_free(&s->alloc, bx, (size_t)(s->alive ? s->alive : 1) * sizeof *bx);
    if (st != PX_OK) return st;
    out->contact = out->distance <= s->margin;
    return PX_OK;
}
