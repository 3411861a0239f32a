/// proxima: exact, fast proximity queries between rigid convex polytopes.
///
/// The umbrella header: the whole public API.
///   proxima/base.h    export macro, version, statuses and errors, allocator
///   proxima/math.h    vectors and poses
///   proxima/convex.h  convex polytopes
///   proxima/mesh.h    triangle meshes with their part tree (assemblies)
///   proxima/query.h   distance, intersection and collision translation
///   proxima/model.h   non-convex models (hierarchies of convex pieces)
///   proxima/scene.h   many moving bodies: broad phase and pair scheduling
///   proxima/chain.h   articulated chains (robot arms) as scene bodies
///   proxima/io.h      meshes and polytopes from files (Assimp; link proxima-io)
///   proxima/urdf.h    robots from URDF files as chains (libxml2; link proxima-io)
///
/// C11, no global state beyond the file-import lock of io.h. Geometry
/// objects are immutable after creation and may be shared between threads;
/// everything a query changes lives in small caller-owned caches.
#ifndef PROXIMA_PROXIMA_H
#define PROXIMA_PROXIMA_H

#include "proxima/base.h"
#include "proxima/chain.h"
#include "proxima/convex.h"
#include "proxima/io.h"
#include "proxima/math.h"
#include "proxima/mesh.h"
#include "proxima/model.h"
#include "proxima/query.h"
#include "proxima/scene.h"
#include "proxima/urdf.h"

#endif /* PROXIMA_PROXIMA_H */
