/// proxima/io.h: meshes and polytopes from mesh files (Assimp). These
/// functions live in the separate library proxima-io (CMake target
/// proxima::io, pkg-config proxima-io), the only part of proxima that links
/// Assimp.
///
/// Any format Assimp 5 reads (OBJ, STL, PLY, OFF, COLLADA, glTF, FBX, ...),
/// except those refused below (see Limits), can be loaded as a `px_mesh`
/// (triangles and the file's part tree, `px_mesh_load`) or turned into a
/// convex polytope: the convex hull of every vertex of every mesh in the
/// file (`px_convex_create_from_file`).
/// Positions pass through Assimp as 32-bit floats (about 7 significant
/// digits), except that `px_mesh_load` reads plain OFF, ASCII STL, OBJ and
/// PLY-of-doubles coordinates again at full precision (docs/io.md says
/// when); do not route precision-critical geometry through other files.
///
/// Frames and units: the node tree of the file is applied, so vertices are in
/// the file's root ("scene") frame. No unit conversion is made by proxima:
/// STL/OBJ/PLY/OFF have no units (the numbers in the file are used as they
/// are); for COLLADA, Assimp folds `<unit meter>` and the up-axis rotation
/// into the root node, so those come out in metres, Y up.
///
/// Thread safety: imports are serialised internally (Assimp's last-error
/// string is process-global); the functions may be called from any thread.
/// The lock is the library's only global state. It is created on first use;
/// should that fail (mtx_init), every load fails with PX_ERR_INTERNAL
/// instead of calling Assimp unlocked. The checks below run before the lock
/// is taken, and no file is ever opened in a way that can block while it is
/// held.
///
/// Files Assimp opens: the import reads through proxima's own file system
/// (Assimp's aiFileIO), for the mesh file and every file it references (glTF
/// buffers, an OBJ material library, ...). Each must be a regular file
/// (stat() before opening, and opened with O_NONBLOCK: a FIFO or device is
/// refused, never waited on) of at most PX_IO_MAX_FILE_BYTES, and all of
/// them together may hold PX_IO_MAX_IMPORT_BYTES (each opening Assimp reads
/// from counts the file's size; the mesh file counts once). The mesh file
/// must still be the file that was checked (same device, inode, size and
/// modification time). A refused file fails the import with PX_ERR_IO naming
/// it and why, also where Assimp would have gone on without it (an OBJ
/// material library); a missing referenced file is left to Assimp.
/// References are resolved as the format defines them, relative to the mesh
/// file's directory, ".." included: the import is not confined to that
/// directory (a glTF buffer "../x.bin" is a legitimate reference). Loading a
/// file thus reads any regular file within the limits that the calling
/// process may read and the file names; do not load untrusted files with
/// privileges the file's author should not have.
///
/// Limits: a file is checked before Assimp reads it, so that a lying or
/// malformed file cannot make the import allocate memory the file cannot
/// back, loop forever, or crash Assimp 5.2 (Debian bookworm's 5.2.5, whose
/// readers the checks follow). Headers are read from the first 64 KiB; PLY
/// and OFF bodies are walked through once; ASCII STL, COLLADA, glTF, AC3D,
/// FBX, OpenGEX and XML documents are read whole. Refused with PX_ERR_IO, the
/// message naming the file and the problem:
/// - anything but a regular file (directory, device, pipe), an empty file,
///   or a file of more than PX_IO_MAX_FILE_BYTES;
/// - an OFF, PLY or binary STL file whose header declares more vertices,
///   faces or other elements than its size can hold (each at its smallest
///   encoding: OFF one line of 2 bytes per vertex and face; PLY the bytes of
///   one record, lists empty; binary STL exactly 84 + 50 n bytes for n
///   triangles), or more than PX_IO_MAX_ELEMENTS in total (an STL triangle
///   counts 4: 3 vertices and a face); an OFF or PLY header that does not end
///   within the first 64 KiB; a `.stl` file that is neither a binary STL of
///   consistent size nor ASCII text starting with `solid`;
/// - PLY: any file whose first line starts with "ply" in any case, whatever
///   follows on that line (as Assimp detects PLY), is read as Assimp reads it:
///   refused are a header Assimp would loop on (no `end_header` line it
///   reaches), a comment line among an element's properties (Assimp makes
///   it an element that takes the properties after it), a line break other
///   than "\n" or "\r\n" that makes it read past its buffer, a property
///   type it does not read or a property line without a name, several
///   vertex elements or several face/tristrips elements, any tristrips
///   records (Assimp 5.2 keeps only each strip's last triangle), records that do
///   not fit in the file (binary) or on their line (ascii: one record per
///   line, every value a number of its property's type), a list declaring
///   more values than the bytes left (binary) or its line (ascii) can hold,
///   or more than PX_IO_MAX_PLY_LIST, lists holding more than
///   4 * PX_IO_MAX_ELEMENTS values in all, and a face whose 6 to 8 texcoord
///   values outnumber its vertex indices;
/// - OFF: the vertex and face lines are read as Assimp reads them: refused
///   are a text that ends before its declared vertices and faces, a line of
///   4096 bytes or more, a face of fewer than 3 vertices, with an index that
///   is not a number below the vertex count or with fewer indices than its
///   count, more faces of 10 or more vertices (which Assimp drops) than the
///   declared face count, a face line after the declared faces (Assimp
///   drops it), and a UTF-16 byte-order mark; and, since review
///   s30, any face of 10 or more vertices (Assimp drops it, so the mesh
///   would lack its triangles; the points loaders, built on px_mesh_load,
///   refuse it too);
/// - ASCII STL (text starting with `solid`): the solids are read as Assimp
///   reads them; refused: keywords in upper case (`SOLID`: Assimp reads
///   lower case only) and, with the line, a facet without `normal`, a
///   normal or vertex without three numbers on its line, a vertex before
///   any facet or a fourth one in a facet (Assimp drops it), a facet of
///   fewer than three vertices, a number with more than 19 digits before
///   its point or in its exponent (Assimp reads one above 2^64 as 0), a
///   NUL byte (Assimp stops there), text after a solid that does not start
///   another when a line starting with `solid` or `facet` follows it
///   (Assimp stops there too) and a solid
///   name over 1023 bytes;
/// - OBJ: a line that starts with blank space (not a continuation, blank or
///   comment line), which Assimp 5.2 skips whole, losing the vertex, face
///   or object it holds; a vertex line of other than 3 (x y z), 4 (x y z w;
///   Assimp divides by w, and refuses w = 0) or 6 (x y z r g b) numbers,
///   counting words that start with a digit, a sign, "nan" or "inf" (so
///   7 numbers, or ".5"; Assimp would drop the vertex); a comment after a
///   face, line or point on its line (Assimp fails on it); and three kinds
///   of valid point cloud (vertices without any f, l or p line) that Assimp
///   5.2 cannot read: one with an `o` or `g` line (its vertices go into no
///   mesh), one with fewer `vn` lines than vertices, one where some but not
///   all vertices have a colour. These checks also run on a file of another
///   name that Assimp reads as OBJ (it picks the OBJ importer by content
///   for a `.txt`, a `.dat` or no extension);
/// - COLLADA and glTF node graphs: a cycle (a node its own descendant,
///   through nesting, <instance_node> or glTF "children"), a node expanding
///   to more than PX_IO_MAX_NODES node instances or a file defining more
///   than PX_IO_MAX_NODES nodes, a chain of more than 256 nodes, XML nested
///   more than 512 elements or JSON more than 128 levels deep, and what the
///   check does not decode: COLLADA node ids, names and instance_node urls
///   with a character reference, tab or line break, glTF member names with
///   escapes, duplicate glTF "nodes", "scenes" or "children" members, and
///   glTF 1.0 nodes with children; a glTF or JSON file that is not valid
///   JSON;
/// - COLLADA: an <accessor> that reads past its source array, that is
///   offset + (count - 1) * stride + (its <param>s, a float4x4 counting 16)
///   values beyond the count attribute of the <float_array>, <Name_array> or
///   <IDREF_array> (none without it: Assimp reads that many values and then
///   indexes past them), and accessor or array counts, offsets and strides
///   that are not plain numbers below 2^31; <p> and <vcount> numbers that are negative
///   or above 2^31 - 1, and numbers in <float_array>, transform elements or
///   <unit meter> of 2^64 or more before the point or with an exponent of
///   2^32 or more (Assimp 5.2 wraps the first and reads the second as 0);
///   and any <controller> (skin or
///   morph: Assimp 5.2 allocates by the sum of <vcount> and indexes bones,
///   weights and vertices by <v> unchecked);
/// - glTF sparse accessors (Assimp 5.2 reads them unchecked: a missing
///   "indices" crashes it, and it allocates count * element size for one
///   without a buffer view), and glTF files that use KHR_mesh_quantization
///   or EXT_meshopt_compression (Assimp 5.2 takes their integer positions
///   for float bits);
/// - glTF 2.0 accessors of the meshes a scene uses (indices, POSITION, the
///   other attributes and morph targets) that read past their buffer view
///   (byteOffset + (count - 1) * stride + element size beyond its
///   byteLength), whose view runs past its buffer's byteLength, whose
///   byteStride is smaller than an element or whose view does not exist
///   (Assimp 5.2 checks only count * component size and read the rest from
///   the heap), POSITION accessors that are not VEC3 of 5126 floats and
///   index accessors that are not unsigned integer SCALARs;
/// - nesting deeper than Assimp 5.2's recursive readers can take on the
///   stack: more than 256 levels of AC3D objects (kids), FBX scopes (ASCII
///   or binary) or OpenGEX structures, and XML (X3D, XGL, AMF,
///   Irrlicht, Ogre and any file read as XML) nested more than 512 elements
///   deep; XML in UTF-16 (COLLADA included), and AC3D or OpenGEX text with
///   a UTF-16 byte-order mark, which the checks do not decode;
/// - AC3D: a kids, numvert, numsurf or refs count above the bytes after it,
///   a numsurf count exceeding the surfaces that follow by more than 65536
///   (Assimp re-reads one line per missing surface), a MATERIAL line holding
///   OBJECT;
/// - XGL: a value list with an integer followed by a comma and a digit
///   ("0,0,1"; "0, 0, 1" and "0.0,0.0,1.0" are fine), which Assimp 5.2 reads
///   with the comma as a decimal point, returning other points than the
///   file's;
/// - ZGL (compressed XGL) files and gzip-compressed Blender files: Assimp
///   5.2 inflates them whole, to whatever size they expand;
/// - BVH files (.bvh, or starting with HIERARCHY): a skeleton and its
///   motion, no mesh; Assimp 5.2 makes up a mesh around the bones, which
///   would come back as the file's points;
/// - ZIP archives (.zae, .3mf, .pk3, .ifczip, and files ending like a ZIP
///   archive under names that do not pin a non-ZIP format): Assimp inflates
///   the files in them unchecked;
/// - DirectX (.x), ASE (.ase, .ask), MD5 (.md5mesh, .md5anim, .md5camera),
///   NFF (.nff, .enff) and Caligari (.cob, .scn) files, also X, ASE and MD5
///   content under another name: Assimp 5.2 sizes arrays by counts written
///   anywhere in them, which no header check can bound;
/// - files starting with 00 00 FE FF or FE FF 00 00, which Assimp 5.2 takes
///   for UTF-32 byte-order marks and mishandles;
/// - a scene with more than PX_IO_MAX_ELEMENTS vertices, counting a mesh once
///   per node that references it.
/// At these limits, the arrays Assimp sizes by declared counts take about
/// 2 GiB at most (up to ~64 bytes per element). Once Assimp's scene is
/// released, `px_mesh_load` holds at most about 84 bytes per vertex and 48
/// per triangle while it builds the mesh (its arrays, the mesh's copy, the
/// closed test's sorting), 4.1 GiB at 2^25 of each; the point loaders then
/// keep 24 bytes per vertex (48 while duplicates are removed).
#ifndef PROXIMA_IO_H
#define PROXIMA_IO_H

#include <stddef.h>

#include "proxima/base.h"
#include "proxima/convex.h"
#include "proxima/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Largest mesh file accepted, in bytes (1 GiB).
#define PX_IO_MAX_FILE_BYTES (1ull << 30)

/// Largest total of the element counts a file header may declare, and the
/// most vertices one load may collect from a scene (2^25 = 33554432).
#define PX_IO_MAX_ELEMENTS (1ull << 25)

/// Most bytes the files one import reads may hold together (1 GiB, as much
/// as one file may): the mesh file once, and each file it references (glTF
/// buffers, an OBJ material library, ...) with its whole size for each time
/// Assimp opens and reads it.
#define PX_IO_MAX_IMPORT_BYTES PX_IO_MAX_FILE_BYTES

/// Most values one PLY list may declare (2^24 = 16777216). All lists of a
/// file together may hold at most 4 * PX_IO_MAX_ELEMENTS values.
#define PX_IO_MAX_PLY_LIST (1ull << 24)

/// Most node instances a COLLADA or glTF node may expand to, and most nodes
/// such a file may define (2^16 = 65536): Assimp builds one node per path
/// from the root through instances and children.
#define PX_IO_MAX_NODES (1ull << 16)

/// Loads the mesh file at `path` as a `px_mesh` (proxima/mesh.h): one part
/// per node that references meshes, holding all of them (Assimp splits one
/// geometry into a mesh per material, so its meshes are not the file's
/// bodies; what one node holds moves as one), so a mesh that two nodes
/// reference gives two parts. Parts come in the order of a depth-first walk
/// of the file's node tree, with the node's world transform applied
/// (vertices in the file's root frame), and the tree is kept as the mesh's
/// nodes (preorder: parents before children). A part hangs from its node
/// and is named "node/mesh" after the node and its first mesh (Assimp's
/// names: COLLADA node ids, OBJ object names, ...; "node/#k" when that is
/// the file's k-th mesh and has no name).
///
/// What a part holds: every vertex of its meshes, in Assimp's order (so STL
/// parts have 3 vertices per triangle: nothing is welded; the closed test
/// joins exactly equal positions itself), and the mesh's faces as
/// triangles (a polygon of n corners becomes n - 2 triangles of its
/// corners by our ear clipping, not Assimp's, which filled the notches of
/// concave polygons; a polygon whose edges cross is refused; points and
/// lines add no triangle, so a mesh of points or lines only is a
/// point-set part). Triangles under a mirroring node transform are
/// reversed, so their winding keeps facing the same way. No other Assimp
/// post-processing runs: joining vertices, removing degenerate triangles
/// and validating the scene all use absolute thresholds in file units and
/// delete small parts of small models (docs/io.md). The closed test and the
/// flip of inside-out closed parts are `px_mesh_create`'s.
///
/// Units: `options->scale` (0: 1) multiplies every coordinate. The mesh's
/// `unit_metres` is 1 for COLLADA (Assimp folds `<unit meter>` and the
/// up-axis rotation into the root node, so the coordinates are already
/// metres, Y up) and glTF, 0 (unknown) for the other formats.
/// Precision: Assimp 5.2 stores positions as 32-bit floats (docs/io.md has
/// the measured cost: up to 5.9e-8 relative, 1.43 half-ulps). Plain OFF,
/// ASCII STL, OBJ and PLY files of double coordinates are read again at
/// full precision (strtod), the rest of the mesh still Assimp's (docs/io.md lists the files left to
/// the floats); `px_mesh_info.float_coordinates` is 0 then, 1
/// when the coordinates are Assimp's floats.
///
/// Returns NULL and fills `err` (may be NULL) on:
/// - PX_ERR_INVALID_ARGUMENT: `path` NULL or empty, a reserved option not
///   zero, a scale that is negative, NaN or infinite, an allocator without
///   both functions;
/// - PX_ERR_IO: everything `px_convex_create_from_file` refuses (the file's
///   checks and limits, Assimp's failures), and a face index out of its
///   mesh's range (for glTF, whose importer drops such a triangle with a
///   warning only: fewer triangles than the primitives the scene reaches
///   define, n / 3 for a triangle list (mode 4) of n indices, or of n
///   vertices without indices, n - 2 for a strip or fan (modes 5 and 6),
///   degenerate ones included, none for points and lines (modes 0 to 3),
///   whose every vertex is kept as a point; and, named by mesh and
///   primitive, a triangle list of n not a multiple of 3, a strip or fan of
///   n < 3, a line strip or loop of n < 2, a mode other than 0 to 6), a
///   NaN or infinite coordinate (also after the node
///   transform or the scale), polygons too large to triangulate (the
///   squares of the sizes of all polygons of 5 or more corners sum to more
///   than 2^28: ear clipping is quadratic), more than PX_IO_MAX_ELEMENTS
///   vertices, triangles, parts or nodes (a mesh counts once per node that
///   uses it), a file with no vertex. The message names the file;
/// - PX_ERR_INTERNAL: the import lock could not be created;
/// - PX_ERR_OUT_OF_MEMORY.
PX_API px_mesh *px_mesh_load(const char *path, const px_mesh_options *options, px_error *err);

/// Convex hull of all vertices of all meshes in the file at `path`, with the
/// node transforms applied (the file's root frame; see the header comment for
/// units). A mesh referenced by several nodes contributes one copy per node.
/// Points, lines and faces all count. Vertices no face uses count for PLY,
/// OFF and glTF (whose readers keep every vertex listed) and for files that
/// have only vertices (an OBJ point cloud; Limits lists those Assimp 5.2
/// cannot read, refused), but not for OBJ and COLLADA files
/// with faces: Assimp 5.2 builds their meshes from the faces and drops the
/// other vertices, and offers no option to keep them (STL has no vertex
/// list). The file is read by `px_mesh_load` (default options) and the
/// hull built from its vertices, exact duplicates removed (`px_load_points`).
/// `options` (may be NULL) is passed to `px_convex_create`.
///
/// Returns NULL and fills `err` (may be NULL) on:
/// - PX_ERR_INVALID_ARGUMENT: `path` NULL or empty;
/// - PX_ERR_IO: whatever `px_mesh_load` refuses: the file cannot be opened,
///   exceeds a limit or fails a check of its header (see the header
///   comment), Assimp cannot parse it or reports an incomplete scene, the
///   scene has no meshes or no vertices, a face index is out of its mesh's
///   range, polygons are too large to triangulate, or a vertex (in any
///   mesh, or after the node transform) is NaN or infinite. The message
///   names the file and the problem (Assimp's own message is quoted when
///   there is one);
/// - PX_ERR_INTERNAL: the import lock could not be created (see Thread
///   safety);
/// - PX_ERR_DEGENERATE: the vertices have no 3-D hull (flat, collinear, one
///   point): the message names the file;
/// - PX_ERR_OUT_OF_MEMORY.
PX_API px_convex *px_convex_create_from_file(const char *path, const px_convex_options *options,
                                             px_error *err);

/// The distinct vertex positions of all meshes in the file at `path`, node
/// transforms applied (the frame `px_convex_create_from_file` uses). On
/// PX_OK, `*xyz` holds `3 * *count` doubles (x, y, z per point, exact
/// duplicates removed, order unspecified but deterministic), allocated with
/// `allocator` (NULL: malloc; the mesh `px_mesh_load` reads on the way
/// uses it too): release it with `px_free_points(*xyz, *count, allocator)`,
/// the same allocator.
/// On error `*xyz` is NULL, `*count` is 0, and the status is returned with
/// `err` (may be NULL) filled as for `px_convex_create_from_file` (PX_ERR_IO,
/// PX_ERR_INVALID_ARGUMENT for a NULL argument or an allocator without both
/// functions, PX_ERR_INTERNAL, PX_ERR_OUT_OF_MEMORY).
PX_API px_status px_load_points(const char *path, const px_allocator *allocator, double **xyz, size_t *count,
                                px_error *err);

/// Frees an array returned by `px_load_points`; `count` and `allocator`
/// must be the ones it was returned with. NULL is a no-op.
PX_API void px_free_points(double *xyz, size_t count, const px_allocator *allocator);

#ifdef __cplusplus
}
#endif

#endif /* PROXIMA_IO_H */
