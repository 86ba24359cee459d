/** @file rugo/baked.h
 * librugo — baked shapes: a built rugo_shape stored as a binary file, loaded without rebuilding.
 *
 * A baked file holds everything a shape holds (pyramid of every level with its details, λ and β of
 * every level, the per-segment band bounds, the MOBBtree, mass properties, friction map and
 * restitution) in a versioned, little-endian format with a 64-bit checksum; docs/baked.md describes it
 * byte by byte. Loading copies the stored values instead of recomputing them, so a loaded shape gives
 * bit-identical query results to the shape that was baked, on any host with IEEE-754 doubles.
 *
 * The loader never trusts its input: it checks the magic, version, sizes, checksum and then every
 * field before use (levels, counts within RUGO_MAX_CONTROL_POINTS, enums, finite values of bounded
 * magnitude, non-negative tolerances and half-extents, unit box axes, mass, surface parameters, a
 * counter-clockwise finest outline). It does not repeat the self-intersection test of a build (that
 * is the cost baking saves): the checksum catches corruption, not a deliberately crafted file whose
 * outline crosses itself; such a file gives a usable shape whose contacts may be meaningless. */
#ifndef RUGO_BAKED_H
#define RUGO_BAKED_H

#include "rugo/base.h"
#include "rugo/shape.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The format version this library writes and the only one it reads. */
#define RUGO_BAKED_VERSION 1
/** Length of the magic bytes at offset 0 ("RUGOBAKE"). */
#define RUGO_BAKED_MAGIC_SIZE 8
/** Largest baked file accepted or written (512 MiB; a shape of RUGO_MAX_CONTROL_POINTS points needs
 * about 260 MiB). Bounds what a hostile header can make the loader read. */
#define RUGO_MAX_BAKED_BYTES ((size_t)512 << 20)

/** Where and why loading or writing failed: the byte offset of the offending field in the file (0 if
 * not applicable), its name (e.g. "tree.nodes[12].half[1]") and a message. Always NUL-terminated. */
typedef struct rugo_baked_error {
    size_t offset;     /**< byte offset of the offending field (0 if not applicable) */
    char field[64];    /**< the field's name, e.g. "tree.nodes[12].half[1]" (may be empty) */
    char message[160]; /**< what is wrong, in English */
} rugo_baked_error;

/** true if the buffer starts with the magic bytes of a baked shape (use it to tell a baked file from a
 * JSON one: a JSON text cannot start with them). false for NULL or a shorter buffer. */
RUGO_API bool rugo_is_baked(const void* buffer, size_t size);

/** Bytes rugo_shape_bake writes for this shape, into *size. Errors: NULL_ARGUMENT, TOO_LARGE (beyond
 * RUGO_MAX_BAKED_BYTES). */
RUGO_API rugo_status rugo_shape_bake_size(const rugo_shape* shape, size_t* size);

/** Writes the shape into buffer (capacity bytes, caller-owned). *written receives the size (also on
 * TOO_LARGE, the capacity needed). Errors: NULL_ARGUMENT, TOO_LARGE (capacity below rugo_shape_bake_size, or
 * the shape beyond RUGO_MAX_BAKED_BYTES). Deterministic: the same shape gives the same bytes. */
RUGO_API rugo_status rugo_shape_bake(const rugo_shape* shape, void* buffer, size_t capacity, size_t* written);

/** Loads a baked shape from memory (size bytes; the buffer is only read and may be freed afterwards).
 * The shape allocates with `allocator` (NULL = malloc/free); destroy it with rugo_shape_destroy.
 * Errors, checked in this order: NULL_ARGUMENT; TRUNCATED (shorter than the header, or than the sizes
 * the header gives); BAD_FORMAT (wrong magic, header size or reserved bytes); BAD_VERSION; TOO_LARGE
 * (the header's size beyond RUGO_MAX_BAKED_BYTES); BAD_FORMAT (bytes after the payload); CHECKSUM;
 * BAD_FORMAT (any field out of range, a payload whose length does not match its levels);
 * OUT_OF_MEMORY. detail may be NULL. On error *out is NULL. */
RUGO_API rugo_status rugo_shape_load_baked(const void* buffer, size_t size, const rugo_allocator* allocator,
                                           rugo_shape** out, rugo_baked_error* detail);

/** Replaces how rugo_shape_write_baked_file writes bytes, so that tests can simulate a full disk.
 * write(data, size, ctx) returns the bytes it accepted (fewer = failure). */
typedef struct rugo_baked_write_hook {
    /** Offered each chunk before it is written; returns how many bytes it accepts. */
    size_t (*write)(const void* data, size_t size, void* ctx);
    void* ctx; /**< passed unchanged to write */
} rugo_baked_write_hook;

/** Writes the shape to `path` atomically: into a new temporary file in the same directory, flushed and
 * fsync'ed, then renamed over `path` (and the directory fsync'ed where POSIX allows). On any error the
 * temporary file is removed and an existing file at `path` is left untouched. The file gets mode
 * 0644 on POSIX. hook may be NULL; when given, each chunk is first offered to hook->write and only the
 * bytes it accepts are written, a short count failing the write like a full disk. allocator (NULL =
 * malloc/free) holds the bytes meanwhile. Errors: NULL_ARGUMENT, TOO_LARGE, OUT_OF_MEMORY, IO (detail names
 * the step). */
RUGO_API rugo_status rugo_shape_write_baked_file(const rugo_shape* shape, const char* path,
                                                 const rugo_allocator* allocator,
                                                 const rugo_baked_write_hook* hook, rugo_baked_error* detail);

/** Reads and loads a baked file (path: a file name, not kept). On success *out is a new shape owned by
 * the caller (free with rugo_shape_destroy); on error NULL. detail may be NULL. Errors: those of
 * rugo_shape_load_baked, IO (cannot open or read), TOO_LARGE (a file beyond RUGO_MAX_BAKED_BYTES, refused
 * before reading it). */
RUGO_API rugo_status rugo_shape_read_baked_file(const char* path, const rugo_allocator* allocator,
                                                rugo_shape** out, rugo_baked_error* detail);

#ifdef __cplusplus
}
#endif

#endif
