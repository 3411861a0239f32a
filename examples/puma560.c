/* The Puma 560 arm: kinematics, link models, scene bodies (puma560.h has
 * the frames and the sources). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* stat */
#endif
#include "puma560.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "proxima/io.h"

#define PI 3.14159265358979323846

/* Joint limits (deg) of the DH table (RTB-Python Puma560.py after Wang and
 * Chen 1991): -160..160, then for joints 2 and 3 the alternative of the
 * source's comment, -45..225 and -225..45 (the main ones, -110..110 and
 * -135..135, exclude the source's own nominal pose qn = (0, 45, 180, 0,
 * 45, 0) deg and every elbow-up reach in front of the arm), then
 * -266..266, -100..100, -266..266. */
const double puma_q_min[PUMA_JOINTS] = {-160 * PI / 180, -45 * PI / 180,  -225 * PI / 180,
                                        -266 * PI / 180, -100 * PI / 180, -266 * PI / 180};
const double puma_q_max[PUMA_JOINTS] = {160 * PI / 180, 225 * PI / 180, 45 * PI / 180,
                                        266 * PI / 180, 100 * PI / 180, 266 * PI / 180};
/* Ours: the arm joints slower than the wrist. */
const double puma_qd_max[PUMA_JOINTS] = {1.0, 1.0, 1.0, 2.0, 2.0, 2.0};

/* q_urdf = q_dh + offset. Found by a search over signs and multiples of
 * pi/2: the offsets of joints 1-3 that put the wrist centre nearest the
 * DH table's, then those with which every link frame's rotation is the DH
 * frame's times a constant, at random configurations (tests/test_puma.c
 * checks both). Every joint turns in the DH sense. nimasarli's forearm
 * hangs down at its q3 = 0 (offset pi); its joint 4 then needs pi too
 * (else joint 5 turns the other way). With these offsets both chains give
 * every link the same orientation. */
const double puma_urdf_offset[PUMA_MESH_SETS][PUMA_JOINTS] = {
    {0, 0, PI, PI, 0, 0},
    {0, 0, 0, 0, 0, 0},
    {0, 0, 0, 0, 0, 0},
};

px_pose puma_compose(const px_pose *a, const px_pose *b) {
    px_pose out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.r[3 * i + j] =
                a->r[3 * i] * b->r[j] + a->r[3 * i + 1] * b->r[3 + j] + a->r[3 * i + 2] * b->r[6 + j];
    out.t = px_pose_apply(a, b->t);
    return out;
}

px_pose puma_inverse(const px_pose *a) {
    px_pose out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out.r[3 * i + j] = a->r[3 * j + i];
    out.t.x = -(out.r[0] * a->t.x + out.r[1] * a->t.y + out.r[2] * a->t.z);
    out.t.y = -(out.r[3] * a->t.x + out.r[4] * a->t.y + out.r[5] * a->t.z);
    out.t.z = -(out.r[6] * a->t.x + out.r[7] * a->t.y + out.r[8] * a->t.z);
    return out;
}

/* URDF <origin xyz rpy>: R = Rz(yaw) Ry(pitch) Rx(roll) (fixed axes X, Y, Z). */
px_pose puma_urdf_origin(double x, double y, double z, double roll, double pitch, double yaw) {
    double cr = cos(roll), sr = sin(roll), cp = cos(pitch), sp = sin(pitch), cy = cos(yaw), sy = sin(yaw);
    px_pose p;
    const double r[9] = {cy * cp,
                         cy * sp * sr - sy * cr,
                         cy * sp * cr + sy * sr,
                         sy * cp,
                         sy * sp * sr + cy * cr,
                         sy * sp * cr - cy * sr,
                         -sp,
                         cp * sr,
                         cp * cr};
    memcpy(p.r, r, sizeof r);
    p.t = (px_vec3){x, y, z};
    return p;
}

/* Rotation by q about the unit axis a (Rodrigues). */
px_pose puma_axis_rotation(px_vec3 a, double q) {
    double c = cos(q), s = sin(q), t = 1 - c;
    px_pose p;
    const double r[9] = {t * a.x * a.x + c,       t * a.x * a.y - s * a.z, t * a.x * a.z + s * a.y,
                         t * a.x * a.y + s * a.z, t * a.y * a.y + c,       t * a.y * a.z - s * a.x,
                         t * a.x * a.z - s * a.y, t * a.y * a.z + s * a.x, t * a.z * a.z + c};
    memcpy(p.r, r, sizeof r);
    p.t = (px_vec3){0, 0, 0};
    return p;
}

/* The chains of SOURCE.md: joint origins X_joint_k (k = 1..6: parent link
 * k-1 to link k), the joint axes, and the visual origins X_visual_k. */
typedef struct chain {
    double joint[PUMA_JOINTS][6]; /* xyz rpy */
    int axis_y[PUMA_JOINTS];      /* 1: axis (0 1 0), else (0 0 1) */
    double visual[PUMA_LINKS][6];
} chain;

/* Table 1: nimasarli urdf/puma560_robot.urdf. */
static const chain nimasarli = {
    .joint = {{0, 0, 0.6718, PI / 2, 0, 0},
              {0, 0, 0, 0, 0, 0},
              {0.4318, -0.0203, 0.1501, 0, 0, -PI / 2},
              {0, 0, 0, PI / 2, 0, PI / 2},
              {0, 0, 0.4331, PI / 2, 0, 0},
              {0, 0.0558, 0, -PI / 2, 0, 0}},
    .axis_y = {1, 0, 0, 0, 0, 0},
    .visual = {{0, 0, 0, 0, 0, PI / 2},
               {0, 0, -0.1, 0, 0, 0},
               {0, 0, 0.1936, 0, 0, 0},
               {0, 0, 0, 0, 0, 0},
               {0, 0, 0.3621, 0, 0, PI / 2},
               {0, 0, 0, PI, 0, PI / 2},
               {0, 0, -0.010, 0, 0, 0}},
};

/* Table 2: RTB's puma560_robot.urdf.xacro, with its parameters (m):
 * l1_1 = 0.54864, l2_1 = 0.07493, l2_2 = 0.14224, l3_2 = 0.0254,
 * l3_3 = 0.4318, l4_3 = 0, l4_4z = 0.35179, l4_4y = -0.0381,
 * l5_4 = 0.02032, l5_5 = 0.059979, l6_5 = 0, l6_6 = 0.05334, l7_6 = 0. */
#define L1_1 0.54864
#define L2_1 0.07493
#define L2_2 0.14224
#define L3_2 0.0254
#define L3_3 0.4318
#define L4_3 0.0
#define L4_4Z 0.35179
#define L4_4Y (-0.0381)
#define L5_4 0.02032
#define L5_5 0.059979
#define L6_5 0.0
#define L6_6 0.05334
#define L7_6 0.0
static const chain rtb = {
    .joint = {{0, 0, L1_1, PI / 2, 0, 0},
              {0, L2_1, L2_2, 0, 0, 0},
              {L3_3, 0, L3_2, 0, 0, PI / 2},
              {L4_4Z, 0, L4_4Y + L4_3, -PI / 2, 0, -PI / 2},
              {0, 0, L5_4 + L5_5, PI / 2, 0, 0},
              {0, L6_6 + L6_5, 0, -PI / 2, 0, 0}},
    .axis_y = {1, 0, 0, 0, 0, 0},
    .visual = {{0, 0, 0, 0, 0, 0},
               {0, L2_1, 0, 0, 0, 0},
               {0, 0, L3_2, 0, 0, 0},
               {0, 0, L4_3, 0, 0, 0},
               {0, 0, L5_4, 0, 0, 0},
               {0, 0, L6_5, 0, 0, 0},
               {0, 0, L7_6, 0, 0, 0}},
};

static const chain *chain_of(puma_meshes set) { return set == PUMA_NIMASARLI ? &nimasarli : &rtb; }

static px_pose origin6(const double o[6]) { return puma_urdf_origin(o[0], o[1], o[2], o[3], o[4], o[5]); }

void puma_link_frames(puma_meshes set, const double q[PUMA_JOINTS], px_pose frame[PUMA_LINKS]) {
    const chain *c = chain_of(set);
    frame[0] = px_pose_identity();
    for (int k = 1; k < PUMA_LINKS; ++k) {
        px_pose x = origin6(c->joint[k - 1]);
        px_pose a = puma_compose(&frame[k - 1], &x);
        double qk = q[k - 1] + puma_urdf_offset[set][k - 1];
        px_pose r = puma_axis_rotation(c->axis_y[k - 1] ? (px_vec3){0, 1, 0} : (px_vec3){0, 0, 1}, qk);
        frame[k] = puma_compose(&a, &r);
    }
}

/* The mesh frame of link k in its link frame: X_visual_k, and for the
 * COLLADA files Rx(+pi/2). Assimp 5.2 turns a Z_UP COLLADA file to Y up by
 * multiplying its root node's transform by Rx(-pi/2) ((x, y, z) ->
 * (x, z, -y), ColladaLoader.cpp), and px_mesh_load applies the node
 * transforms, so the loaded vertices are Rx(-pi/2) times the file's (for
 * the collision meshes, times their own node matrix, which SOURCE.md says
 * lines them up with the visual meshes). Rx(+pi/2) undoes it. */
static px_pose mesh_in_link(puma_meshes set, int k) {
    px_pose v = origin6(chain_of(set)->visual[k]);
    if (set == PUMA_NIMASARLI) return v;
    px_pose fix = puma_urdf_origin(0, 0, 0, PI / 2, 0, 0);
    return puma_compose(&v, &fix);
}

void puma_link_poses(puma_meshes set, const double q[PUMA_JOINTS], px_pose pose[PUMA_LINKS]) {
    px_pose frame[PUMA_LINKS];
    puma_link_frames(set, q, frame);
    for (int k = 0; k < PUMA_LINKS; ++k) {
        px_pose m = mesh_in_link(set, k);
        pose[k] = puma_compose(&frame[k], &m);
    }
}

/* Standard DH (RTB-Python Puma560.py): A_i = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i). */
static const double dh_d[PUMA_JOINTS] = {0.67183, 0, 0.15005, 0.4318, 0, 0};
static const double dh_a[PUMA_JOINTS] = {0, 0.4318, 0.0203, 0, 0, 0};
static const double dh_alpha[PUMA_JOINTS] = {PI / 2, 0, -PI / 2, PI / 2, -PI / 2, 0};

void puma_dh_frames(const double q[PUMA_JOINTS], px_pose frame[PUMA_LINKS]) {
    frame[0] = px_pose_identity();
    for (int i = 0; i < PUMA_JOINTS; ++i) {
        double ct = cos(q[i]), st = sin(q[i]), ca = cos(dh_alpha[i]), sa = sin(dh_alpha[i]);
        px_pose a;
        const double r[9] = {ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0, sa, ca};
        memcpy(a.r, r, sizeof r);
        a.t = (px_vec3){dh_a[i] * ct, dh_a[i] * st, dh_d[i]};
        frame[i + 1] = puma_compose(&frame[i], &a);
    }
}

static double norm3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

void puma_motion_bounds(puma_meshes set, const double *qd_max, px_vec3 center[PUMA_LINKS],
                        double speed[PUMA_LINKS], double angular[PUMA_LINKS]) {
    const chain *c = chain_of(set);
    if (!qd_max) qd_max = puma_qd_max;
    for (int k = 0; k < PUMA_LINKS; ++k) {
        /* The link frame's origin in the mesh (body) frame. */
        px_pose m = mesh_in_link(set, k), mi = puma_inverse(&m);
        center[k] = mi.t;
        speed[k] = angular[k] = 0;
        /* Joint j (1..k) sits at link j's origin; link k's origin is at most
         * the sum of |xyz of X_joint_i| for i = j+1..k from it. */
        for (int j = 1; j <= k; ++j) {
            double reach = 0;
            for (int i = j + 1; i <= k; ++i) reach += norm3(c->joint[i - 1]);
            speed[k] += qd_max[j - 1] * reach;
            angular[k] += qd_max[j - 1];
        }
    }
}

static const char *mesh_path(puma_meshes set, int k, char *buf, size_t size, const char *models) {
    if (set == PUMA_NIMASARLI)
        snprintf(buf, size, "%s/puma560/nimasarli_puma560_description/meshes/puma_link%d.stl", models, k + 1);
    else if (set == PUMA_RTB_COLLISION && k < 6)
        snprintf(buf, size, "%s/puma560/rtb_puma560_description/meshes/puma560_collision%d.dae", models,
                 k + 1);
    else
        snprintf(buf, size, "%s/puma560/rtb_puma560_description/meshes/puma560_link%d.dae", models, k + 1);
    return buf;
}

void puma_arm_destroy(puma_arm *arm) {
    for (int k = 0; k < PUMA_LINKS; ++k) {
        px_model_destroy(arm->link[k]);
        px_mesh_destroy(arm->mesh[k]);
    }
    memset(arm, 0, sizeof *arm);
}

static double wall_seconds(void) {
    struct timespec t;
    timespec_get(&t, TIME_UTC);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A model of `mesh` (read from `file`) as `b` says; approximate ones go
 * through the cache folder under `name`. */
static px_model *build_model(const px_mesh *mesh, const char *file, const char *name, puma_build *b,
                             px_error *err) {
    px_model_options o;
    memset(&o, 0, sizeof o);
    o.pieces = b->pieces;
    if (b->pieces != PX_PIECES_APPROXIMATE) return px_model_create_from_mesh(mesh, &o, err);
    o.tolerance = b->tolerance > 0 ? b->tolerance : PX_MODEL_DEFAULT_TOLERANCE;
    o.threads = b->threads;
    char path[1200] = "";
    if (b->cache_dir) {
        snprintf(path, sizeof path, "%s/%s_approx_tol%g.pxm", b->cache_dir, name, o.tolerance);
        struct stat sm, sc;
        if (stat(file, &sm) == 0 && stat(path, &sc) == 0 && sc.st_mtime >= sm.st_mtime) {
            px_error e2;
            px_model *m = px_model_load(path, NULL, &e2);
            px_model_info info;
            if (m && px_model_get_info(m, &info) == PX_OK && info.pieces == PX_PIECES_APPROXIMATE) {
                b->loaded++;
                if (b->verbose)
                    printf("        %-22s loaded from %s (%u piece%s)\n", name, path, info.leaves,
                           info.leaves == 1 ? "" : "s");
                return m;
            }
            px_model_destroy(m);
            printf("        %s: cache %s unusable (%s); building\n", name, path,
                   m ? "not approximate" : e2.message);
        }
    }
    double t0 = wall_seconds();
    px_model *m = px_model_create_from_mesh(mesh, &o, err);
    double t = wall_seconds() - t0;
    if (!m) return NULL;
    b->built++;
    b->build_seconds += t;
    px_model_info info;
    px_model_get_info(m, &info);
    if (b->verbose)
        printf("        %-22s built in %.2f s: %u piece%s, largest h %.2f mm%s%s\n", name, t, info.leaves,
               info.leaves == 1 ? "" : "s", 1e3 * info.max_h, path[0] ? ", saved as " : "", path);
    if (path[0]) {
        /* Written under another name and renamed: a run stopped midway
         * leaves no truncated cache file (px_model_load would refuse it). */
        char tmp[1300];
        snprintf(tmp, sizeof tmp, "%s.tmp", path);
        px_error e2;
        memset(&e2, 0, sizeof e2);
        if (px_model_save(m, tmp, &e2) != PX_OK || rename(tmp, path) != 0) {
            printf("        %s: cannot save the cache %s (%s)\n", name, path, e2.message);
            remove(tmp);
        }
    }
    return m;
}

px_status puma_arm_load(puma_arm *arm, const char *models, puma_meshes set, uint32_t pieces, px_error *err) {
    puma_build b;
    memset(&b, 0, sizeof b);
    b.pieces = pieces;
    return puma_arm_load_with(arm, models, set, &b, err);
}

px_status puma_arm_load_with(puma_arm *arm, const char *models, puma_meshes set, puma_build *b,
                             px_error *err) {
    static const char *set_tag[PUMA_MESH_SETS] = {"nimasarli", "rtb", "rtb-collision"};
    memset(arm, 0, sizeof *arm);
    arm->set = set;
    for (int k = 0; k < PUMA_LINKS; ++k) {
        char path[1024];
        px_mesh_options mo;
        memset(&mo, 0, sizeof mo);
        mo.scale = set == PUMA_NIMASARLI ? 0.0254 : 1.0; /* the STLs are in inches */
        px_mesh *mesh = px_mesh_load(mesh_path(set, k, path, sizeof path, models), &mo, err);
        if (!mesh) {
            puma_arm_destroy(arm);
            return err ? err->code : PX_ERR_IO;
        }
        char name[64];
        snprintf(name, sizeof name, "puma_%s_link%d", set_tag[set], k + 1);
        arm->triangles[k] = px_mesh_triangle_count(mesh);
        arm->link[k] = build_model(mesh, path, name, b, err);
        arm->mesh[k] = mesh;
        if (!arm->link[k]) {
            puma_arm_destroy(arm);
            return err ? err->code : PX_ERR_INTERNAL;
        }
    }
    return PX_OK;
}

px_chain *puma_chain_create(const puma_arm *arm, const double *qd_max, uint32_t group, uint32_t mask,
                            px_error *err) {
    const chain *c = chain_of(arm->set);
    if (!qd_max) qd_max = puma_qd_max;
    px_link_desc link[PUMA_LINKS];
    memset(link, 0, sizeof link);
    for (int k = 0; k < PUMA_LINKS; ++k) {
        px_link_desc *l = &link[k];
        l->model = arm->link[k];
        l->geometry = mesh_in_link(arm->set, k);
        l->group = group;
        l->mask = mask;
        if (k == 0) { /* the pedestal, fixed to the base (the world frame) */
            l->parent = PX_CHAIN_ROOT;
            l->joint = PX_JOINT_FIXED;
            l->origin = px_pose_identity();
            continue;
        }
        int j = k - 1;
        l->parent = (uint32_t)(k - 1);
        l->joint = PX_JOINT_REVOLUTE;
        l->axis = c->axis_y[j] ? (px_vec3){0, 1, 0} : (px_vec3){0, 0, 1};
        /* The URDF turns by q + offset: the offset's turn joins the origin. */
        px_pose x = origin6(c->joint[j]), off = puma_axis_rotation(l->axis, puma_urdf_offset[arm->set][j]);
        l->origin = puma_compose(&x, &off);
        l->q_min = puma_q_min[j];
        l->q_max = puma_q_max[j];
        l->max_speed = qd_max[j];
    }
    px_chain_desc d;
    memset(&d, 0, sizeof d);
    d.links = link;
    d.n_links = PUMA_LINKS;
    d.base = px_pose_identity();
    return px_chain_create(&d, err);
}

/* ---- The trajectory ---- */

/* Waypoints (DH joint angles, rad), chosen with the cell in view (docs/demo.md). */
#define WAYPOINTS 10
#define TOUCH_WAYPOINT 5
#define PILLAR_WAYPOINT 7
static const double waypoint[WAYPOINTS][PUMA_JOINTS] = {
    {0, 1.5708, -1.5708, 0, 0, 0},             /* READY (qr) */
    {-0.1736, 0.9570, -3.3310, 0, -0.7676, 0}, /* over the fixture */
    {-0.1736, 0.7235, -3.3100, 0, -0.5550, 0}, /* down into the fixture */
    {-0.1736, 0.9570, -3.3310, 0, -0.7676, 0}, /* up */
    {0.5136, 0.8214, -2.8471, 0, -1.1159, 0},  /* over the teapot */
    {0.5136, 0.5589, -2.8637, 0, -0.8368, 0},  /* touching the teapot */
    {0.5136, 0.8214, -2.8471, 0, -1.1159, 0},  /* up */
    {1.25, 1.0, -2.6, 0, 1.2, 0},              /* by the pillar */
    {1.0, 1.2, -2.4, 0.5, 1.7, 1.0},           /* wrist folded */
    {0, 1.5708, -1.5708, 0, 0, 0},             /* READY */
};

/* Segment k (from waypoint k to k+1) lasts the time whose cosine blend
 * peaks at 0.9 of the slowest joint's speed limit: peak = pi/2 |dq| / T. */
static double segment_time(int k) {
    double t = 0.05;
    for (int j = 0; j < PUMA_JOINTS; ++j) {
        double need = PI / 2 * fabs(waypoint[k + 1][j] - waypoint[k][j]) / (0.9 * puma_qd_max[j]);
        if (need > t) t = need;
    }
    return t;
}

double puma_trajectory_duration(void) {
    double t = 0;
    for (int k = 0; k + 1 < WAYPOINTS; ++k) t += segment_time(k);
    return t;
}

static double waypoint_time(int w) {
    double t = 0;
    for (int k = 0; k < w; ++k) t += segment_time(k);
    return t;
}

double puma_touch_time(void) { return waypoint_time(TOUCH_WAYPOINT); }

void puma_trajectory(double t, double q[PUMA_JOINTS]) {
    int k = 0;
    double start = 0;
    if (t < 0) t = 0;
    while (k + 2 < WAYPOINTS && t > start + segment_time(k)) start += segment_time(k++);
    double s = (t - start) / segment_time(k);
    if (s > 1) s = 1;
    /* At a waypoint's own time the blend gives it exactly (s = 0 or 1). */
    double w = 0.5 * (1 - cos(PI * s));
    if (s == 1) w = 1;
    for (int j = 0; j < PUMA_JOINTS; ++j) q[j] = waypoint[k][j] + w * (waypoint[k + 1][j] - waypoint[k][j]);
}

/* ---- The work cell ---- */

/* A closed box mesh part: 8 corners (corner i takes the max on axis k when
 * bit k of i is set) and 12 triangles wound outward. */
static const uint32_t box_tris[36] = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                      2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};

/* n boxes (lo, hi corners, body frame) as a mesh of n closed parts, and a
 * model of its triangles. Triangle leaves rather than one convex piece per
 * box: px_model_distance measures a triangle leaf against a convex leaf
 * by building a px_convex of the triangle for the pair (src/model/query.c,
 * mixed_pair), which made the link-table pairs cost hundreds of
 * microseconds; triangle pairs are closed form. Closed parts are solids
 * (a link inside a box touches it). */
static px_status boxes(const double (*lohi)[6], uint32_t n, px_model **model, px_mesh **mesh, px_error *err) {
    double xyz[8 * 3 * 8];
    uint32_t tris[36 * 8];
    px_mesh_part_desc parts[8];
    memset(parts, 0, sizeof parts);
    for (uint32_t b = 0; b < n; ++b) {
        for (int c = 0; c < 8; ++c)
            for (int k = 0; k < 3; ++k) xyz[3 * (8 * b + c) + k] = (c >> k) & 1 ? lohi[b][3 + k] : lohi[b][k];
        for (int i = 0; i < 36; ++i) tris[36 * b + i] = 8 * b + box_tris[i];
        parts[b].node = -1;
        parts[b].first_vertex = 8 * b;
        parts[b].vertex_count = 8;
        parts[b].first_triangle = 12 * b;
        parts[b].triangle_count = 12;
    }
    px_mesh_desc d;
    memset(&d, 0, sizeof d);
    d.xyz = xyz;
    d.vertex_count = 8 * n;
    d.triangles = tris;
    d.triangle_count = 12 * n;
    d.parts = parts;
    d.part_count = n;
    *mesh = px_mesh_create(&d, NULL, err);
    if (!*mesh) return err ? err->code : PX_ERR_INTERNAL;
    px_model_options o;
    memset(&o, 0, sizeof o);
    o.pieces = PX_PIECES_TRIANGLES;
    *model = px_model_create_from_mesh(*mesh, &o, err);
    return *model ? PX_OK : (err ? err->code : PX_ERR_INTERNAL);
}

void puma_cell_destroy(puma_cell *cell) {
    for (int i = 0; i < PUMA_CELL_BODIES; ++i) {
        px_model_destroy(cell->body[i].model);
        px_mesh_destroy(cell->body[i].mesh);
    }
    memset(cell, 0, sizeof *cell);
}

/* The smallest distance between the arm at waypoint w and a cell body. */
static px_status arm_distance(const puma_arm *arm, int w, const puma_cell_body *b,
                              px_model_distance_result *best) {
    double q[PUMA_JOINTS];
    puma_trajectory(waypoint_time(w), q);
    px_pose pose[PUMA_LINKS];
    puma_link_poses(arm->set, q, pose);
    memset(best, 0, sizeof *best);
    best->distance = INFINITY;
    for (int k = 0; k < PUMA_LINKS; ++k) {
        px_model_distance_result r;
        px_status st = px_model_distance(arm->link[k], &pose[k], b->model, &b->pose, NULL, &r);
        if (st != PX_OK) return st;
        if (r.distance < best->distance) *best = r;
    }
    return PX_OK;
}

/* Where the teapot sits before it is moved to touch the gripper. */
#define TEAPOT_SCALE 0.004 /* the trimesh teapot is 63 units long: 25 cm */

/* Table: a top 0.6 x 0.9 x 0.04 m, 0.42 m high, on four legs. */
static const double cell_table[5][6] = {{0.30, -0.45, 0.38, 0.90, 0.45, 0.42},
                                        {0.33, -0.42, 0.00, 0.37, -0.38, 0.38},
                                        {0.83, -0.42, 0.00, 0.87, -0.38, 0.38},
                                        {0.33, 0.38, 0.00, 0.37, 0.42, 0.38},
                                        {0.83, 0.38, 0.00, 0.87, 0.42, 0.38}};
/* Fixture: a base plate and an upright, an L on the table. */
static const double cell_fixture[2][6] = {{0.42, -0.34, 0.42, 0.64, -0.14, 0.45},
                                          {0.60, -0.34, 0.45, 0.64, -0.14, 0.62}};
/* Pillar: a column beside the arm, floor to 1.6 m. */
static const double cell_pillar[1][6] = {{-0.10, 0.55, 0.00, 0.06, 0.71, 1.60}};
static const char *cell_names[PUMA_CELL_BODIES] = {"table", "fixture", "teapot", "pillar"};

px_status puma_cell_build(puma_cell *cell, const char *models, const puma_arm *arm, px_error *err) {
    memset(cell, 0, sizeof *cell);
    const double(*table)[6] = cell_table, (*fixture)[6] = cell_fixture, (*pillar)[6] = cell_pillar;
    const char *const *names = cell_names;
    px_status st;
    if ((st = boxes(table, 5, &cell->body[0].model, &cell->body[0].mesh, err)) != PX_OK ||
        (st = boxes(fixture, 2, &cell->body[1].model, &cell->body[1].mesh, err)) != PX_OK ||
        (st = boxes(pillar, 1, &cell->body[3].model, &cell->body[3].mesh, err)) != PX_OK) {
        puma_cell_destroy(cell);
        return st;
    }
    for (int i = 0; i < PUMA_CELL_BODIES; ++i) {
        cell->body[i].name = names[i];
        cell->body[i].pose = px_pose_identity();
    }
    /* The teapot (trimesh, MIT): exact triangle leaves. */
    char path[1024];
    snprintf(path, sizeof path, "%s/teapot/trimesh_mit/teapot.stl", models);
    px_mesh_options mo;
    memset(&mo, 0, sizeof mo);
    mo.scale = TEAPOT_SCALE;
    cell->body[2].mesh = px_mesh_load(path, &mo, err);
    if (!cell->body[2].mesh) {
        puma_cell_destroy(cell);
        return err ? err->code : PX_ERR_IO;
    }
    px_model_options o;
    memset(&o, 0, sizeof o);
    o.pieces = PX_PIECES_TRIANGLES;
    cell->body[2].model = px_model_create_from_mesh(cell->body[2].mesh, &o, err);
    if (!cell->body[2].model) {
        puma_cell_destroy(cell);
        return err ? err->code : PX_ERR_INTERNAL;
    }
    /* On the table (its base is 0.87 units above z = 0), turned 150 deg. */
    cell->body[2].pose = puma_urdf_origin(0.66, 0.20, 0.42 - 0.87 * TEAPOT_SCALE, 0, 0, 150 * PI / 180);
    /* Move it so that it touches the arm at the touching waypoint: by the
     * smallest distance to any link, along the witness direction (the
     * waypoint was chosen 0.1 mm above it). */
    px_model_distance_result best;
    memset(&best, 0, sizeof best);
    if ((st = arm_distance(arm, TOUCH_WAYPOINT, &cell->body[2], &best)) != PX_OK) {
        puma_cell_destroy(cell);
        return st;
    }
    cell->body[2].pose.t.x += best.point_a.x - best.point_b.x;
    cell->body[2].pose.t.y += best.point_a.y - best.point_b.y;
    cell->body[2].pose.t.z += best.point_a.z - best.point_b.z;
    /* Move the pillar across the floor until it is 15 mm from the arm at
     * the pillar waypoint (along the witness direction's horizontal part;
     * a few rounds, as that part shortens the gap by less than its length). */
    for (int round = 0; round < 6; ++round) {
        if ((st = arm_distance(arm, PILLAR_WAYPOINT, &cell->body[3], &best)) != PX_OK) {
            puma_cell_destroy(cell);
            return st;
        }
        double dx = best.point_a.x - best.point_b.x, dy = best.point_a.y - best.point_b.y;
        double h = sqrt(dx * dx + dy * dy), move = best.distance - 0.015;
        if (h == 0 || fabs(move) < 1e-5) break;
        cell->body[3].pose.t.x += move * dx / h;
        cell->body[3].pose.t.y += move * dy / h;
    }
    return PX_OK;
}

/* n boxes as a model of n point-set pieces (their corners): exact convex leaves. */
static px_model *box_pieces(const double (*lohi)[6], uint32_t n, px_error *err) {
    double xyz[8 * 3 * 8];
    uint32_t end[8];
    for (uint32_t b = 0; b < n; ++b) {
        for (int c = 0; c < 8; ++c)
            for (int k = 0; k < 3; ++k) xyz[3 * (8 * b + c) + k] = (c >> k) & 1 ? lohi[b][3 + k] : lohi[b][k];
        end[b] = 8 * (b + 1);
    }
    return px_model_create_from_points(xyz, end, n, NULL, err);
}

px_status puma_cell_build_coarse(puma_cell *cell, const char *models, const puma_cell *exact,
                                 puma_build *build, px_error *err) {
    memset(cell, 0, sizeof *cell);
    if (build->pieces != PX_PIECES_APPROXIMATE) {
        if (err) {
            memset(err, 0, sizeof *err);
            err->code = PX_ERR_INVALID_ARGUMENT;
            snprintf(err->message, sizeof err->message, "puma_cell_build_coarse: pieces must be approximate");
        }
        return PX_ERR_INVALID_ARGUMENT;
    }
    for (int i = 0; i < PUMA_CELL_BODIES; ++i) {
        cell->body[i].name = cell_names[i];
        cell->body[i].pose = exact->body[i].pose;
    }
    cell->body[0].model = box_pieces(cell_table, 5, err);
    cell->body[1].model = cell->body[0].model ? box_pieces(cell_fixture, 2, err) : NULL;
    cell->body[3].model = cell->body[1].model ? box_pieces(cell_pillar, 1, err) : NULL;
    if (!cell->body[3].model) {
        puma_cell_destroy(cell);
        return err ? err->code : PX_ERR_INTERNAL;
    }
    char path[1024];
    snprintf(path, sizeof path, "%s/teapot/trimesh_mit/teapot.stl", models);
    px_mesh_options mo;
    memset(&mo, 0, sizeof mo);
    mo.scale = TEAPOT_SCALE;
    px_mesh *mesh = px_mesh_load(path, &mo, err);
    if (mesh) cell->body[2].model = build_model(mesh, path, "puma_cell_teapot", build, err);
    px_mesh_destroy(mesh);
    if (!cell->body[2].model) {
        puma_cell_destroy(cell);
        return err ? err->code : PX_ERR_INTERNAL;
    }
    return PX_OK;
}

px_status puma_cell_add(const puma_cell *cell, px_scene *scene, uint32_t group, uint32_t mask,
                        uint32_t ids[PUMA_CELL_BODIES], px_error *err) {
    for (int i = 0; i < PUMA_CELL_BODIES; ++i) {
        px_body_desc d;
        memset(&d, 0, sizeof d);
        d.model = cell->body[i].model;
        d.pose = cell->body[i].pose;
        d.group = group;
        d.mask = mask;
        d.flags = PX_BODY_STATIC;
        px_status st = px_scene_add_body(scene, &d, &ids[i], err);
        if (st != PX_OK) return st;
    }
    return PX_OK;
}
