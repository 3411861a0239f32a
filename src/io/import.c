/* The checked, serialised Assimp import both loaders share (import.h).
 *
 * - Before Assimp sees a file, precheck.c checks its type, its size and the
 *   counts its header declares (Assimp allocates by them), and walks PLY and
 *   OFF bodies and COLLADA and glTF node graphs the way Assimp would.
 * - Assimp opens files through fs.c (aiImportFileEx with our aiFileIO): the
 *   mesh file must still be the one the precheck read, and every file the
 *   import opens, the mesh file's references too, is a regular file within
 *   the size limits. A refused open fails the import even where Assimp would
 *   have done without the file.
 * - Assimp's last-error string is a process-global std::string written
 *   without a lock, so every call into Assimp (import, error copy,
 *   post-processing, the callers' walks, release) runs under one mutex, and
 *   the message is copied at once.
 * - The import itself runs no post-processing; a caller that wants some
 *   (px_mesh_load: Triangulate) gets it only after its own check of the raw
 *   scene (indices, finite coordinates), because Assimp's steps trust what
 *   they read (Triangulate indexes mVertices by the face indices).
 * - Scenes flagged AI_SCENE_FLAGS_INCOMPLETE are rejected.
 */
#include "io/import.h"

#include <stdio.h>
#include <string.h>
#include <threads.h>

#include <assimp/cimport.h>
#include <assimp/scene.h>

#include "core/core.h"
#include "io/fs.h"
#include "io/precheck.h"

/* The import lock, created once (call_once) on first use. If mtx_init fails
 * then, the failure is permanent: every later load fails too, with
 * PX_ERR_INTERNAL, rather than calling Assimp without the lock. */
static once_flag g_io_once = ONCE_FLAG_INIT;
static mtx_t g_io_mutex;
static int g_io_mutex_ok; /* written once, inside call_once */

/* call_once callback: creates the import mutex and records whether it could. */
static void io_mutex_init(void) { g_io_mutex_ok = (mtx_init(&g_io_mutex, mtx_plain) == thrd_success); }

/* Takes the import lock. On PX_OK the caller must call io_unlock; otherwise
 * the lock is not held and err names the file and the failure. */
static px_status io_lock(const char *path, px_error *err) {
    call_once(&g_io_once, io_mutex_init);
    if (!g_io_mutex_ok)
        return pxi_error(
            err, PX_ERR_INTERNAL,
            "cannot import mesh file '%s': the import mutex could not be created (mtx_init failed), "
            "and Assimp is not safe to call without it",
            path);
    if (mtx_lock(&g_io_mutex) != thrd_success)
        return pxi_error(err, PX_ERR_INTERNAL,
                         "cannot import mesh file '%s': locking the import mutex failed", path);
    return PX_OK;
}

/* Releases the lock taken by a successful io_lock. */
static void io_unlock(void) { mtx_unlock(&g_io_mutex); }

/* Copies Assimp's last error (call with the lock held). */
static void ai_message(char *msg, size_t size) {
    const char *ai = aiGetErrorString();
    snprintf(msg, size, "%s", ai && ai[0] ? ai : "unknown error");
}

/* The triangles (faces of 3 indices; points and lines have 1 or 2) of the
 * meshes the node tree reaches from the root, each mesh once: the meshes
 * px_mesh_load reads. (Assimp also loads the meshes of
 * nodes only a skin or an animation names, which no scene reaches; the
 * glTF scan does not count those.) */
static px_status reached_faces(const struct aiScene *scene, const px_allocator *alloc, const char *path,
                               unsigned long long *got, px_error *err) {
    unsigned char *used = pxi_alloc(alloc, scene->mNumMeshes);
    size_t cap = 64, n = 0;
    const struct aiNode **stack = pxi_alloc_array(alloc, cap, sizeof *stack);
    px_status st = PX_OK;
    if (!used || !stack) st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "mesh file '%s': out of memory", path);
    if (st == PX_OK) {
        memset(used, 0, scene->mNumMeshes);
        stack[n++] = scene->mRootNode;
    }
    while (st == PX_OK && n) {
        const struct aiNode *node = stack[--n];
        for (unsigned i = 0; i < node->mNumMeshes; ++i) {
            unsigned m = node->mMeshes[i];
            if (m < scene->mNumMeshes && !used[m] && scene->mMeshes[m]) {
                used[m] = 1;
                const struct aiMesh *mesh = scene->mMeshes[m];
                for (unsigned f = 0; mesh->mFaces && f < mesh->mNumFaces; ++f)
                    *got += mesh->mFaces[f].mNumIndices == 3;
            }
        }
        if (node->mNumChildren > cap - n) {
            size_t nc = 2 * (cap + node->mNumChildren);
            const struct aiNode **w = pxi_alloc_array(alloc, nc, sizeof *w);
            if (!w) {
                st = pxi_error(err, PX_ERR_OUT_OF_MEMORY, "mesh file '%s': out of memory", path);
                break;
            }
            memcpy(w, stack, n * sizeof *w);
            pxi_free(alloc, stack, cap * sizeof *stack);
            stack = w;
            cap = nc;
        }
        for (unsigned i = 0; i < node->mNumChildren; ++i)
            if (node->mChildren[i]) stack[n++] = node->mChildren[i];
    }
    pxi_free(alloc, stack, cap * sizeof *stack);
    pxi_free(alloc, used, scene->mNumMeshes);
    return st;
}

const char *pxi_io_scene_format(const struct aiScene *scene) {
    const struct aiMetadata *md = scene->mMetaData;
    for (unsigned i = 0; md && md->mKeys && md->mValues && i < md->mNumProperties; ++i)
        if (strcmp(md->mKeys[i].data, "SourceAsset_Format") == 0 && md->mValues[i].mType == AI_AISTRING &&
            md->mValues[i].mData)
            return ((const struct aiString *)md->mValues[i].mData)->data;
    return NULL;
}

/* Whether Assimp's OBJ importer made the scene. */
static int obj_scene(const struct aiScene *scene) {
    const char *f = pxi_io_scene_format(scene);
    return f && strcmp(f, "Wavefront Object Importer") == 0;
}

/* Whether the file name ends in ".obj" (any case): the precheck ran the
 * OBJ checks then. */
static int obj_name(const char *path) {
    const size_t n = strlen(path);
    if (n < 4 || path[n - 4] != '.') return 0;
    for (int k = 0; k < 3; ++k)
        if ((path[n - 3 + k] | 0x20) != "obj"[k]) return 0;
    return 1;
}

/* The import proper, with the lock held. */
static px_status import_locked(const char *path, const pxi_file_id *id, const px_allocator *alloc,
                               unsigned post_flags, pxi_io_scene_fn check, pxi_io_scene_fn use, void *ctx,
                               px_error *err) {
    /* fs outlives the scene: the importer keeps it until aiReleaseImport. */
    pxi_io_fs fs;
    pxi_io_fs_init(&fs, path, id, alloc);
    const struct aiScene *scene = aiImportFileEx(path, 0, &fs.io);
    if (fs.refused) {
        /* Also after a success: Assimp goes on without a material library. */
        if (scene) aiReleaseImport(scene);
        pxi_io_fs_finish(&fs);
        return pxi_error(err, fs.out_of_memory ? PX_ERR_OUT_OF_MEMORY : PX_ERR_IO,
                         "cannot import mesh file '%s': %s", path, fs.message);
    }
    if (!scene) {
        pxi_io_fs_finish(&fs);
        char msg[160];
        ai_message(msg, sizeof msg);
        return pxi_error(err, PX_ERR_IO, "cannot import mesh file '%s': %s", path, msg);
    }
    px_status st = PX_OK;
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' was imported incompletely (AI_SCENE_FLAGS_INCOMPLETE)",
                       path);
    } else if (scene->mNumMeshes == 0 || !scene->mMeshes) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' contains no meshes", path);
    } else if (!scene->mRootNode) {
        st = pxi_error(err, PX_ERR_IO, "mesh file '%s' has no root node", path);
    }
    /* Read as OBJ under another name: the OBJ checks now. */
    if (st == PX_OK && obj_scene(scene) && !obj_name(path)) st = pxi_io_check_as_obj(path, alloc, id, err);
    if (st == PX_OK && id->gltf_triangles != ~0ull) {
        /* glTF2Importer drops a triangle (of a list, a strip or a fan) with
         * an index out of range, a warning only: the counts tell. */
        unsigned long long got = 0;
        st = reached_faces(scene, alloc, path, &got, err);
        if (st == PX_OK && got < id->gltf_triangles)
            st = pxi_error(err, PX_ERR_IO,
                           "mesh file '%s': %llu of its %llu glTF triangles have a vertex index out of range "
                           "(Assimp 5.2 dropped them)",
                           path, id->gltf_triangles - got, id->gltf_triangles);
    }
    if (st == PX_OK && check) st = check(path, id, scene, ctx, err);
    if (st == PX_OK && post_flags) {
        /* On failure Assimp releases the scene itself and returns NULL. */
        const struct aiScene *post = aiApplyPostProcessing(scene, post_flags);
        if (!post) {
            char msg[160];
            ai_message(msg, sizeof msg);
            pxi_io_fs_finish(&fs);
            return pxi_error(err, PX_ERR_IO, "mesh file '%s': Assimp's post-processing failed: %s", path,
                             msg);
        }
        scene = post;
    }
    if (st == PX_OK && use) st = use(path, id, scene, ctx, err);
    aiReleaseImport(scene);
    pxi_io_fs_finish(&fs);
    return st;
}

px_status pxi_io_import(const char *path, const px_allocator *alloc, unsigned post_flags,
                        pxi_io_scene_fn check, pxi_io_scene_fn use, void *ctx, px_error *err) {
    /* Readability, size and header counts first (precheck.c): Assimp's message
     * for a missing file omits why, and Assimp allocates by declared counts. */
    pxi_file_id id;
    px_status st = pxi_io_precheck(path, alloc, &id, err);
    if (st != PX_OK) return st;
    st = io_lock(path, err);
    if (st != PX_OK) return st;
    st = import_locked(path, &id, alloc, post_flags, check, use, ctx, err);
    io_unlock();
    return st;
}
