/* Baked shapes as files (baked.h): written atomically (a temporary file next to the destination, flushed
 * and synced, renamed over it), read whole with a bound, then loaded by baked.c. */
#if defined(__unix__) || defined(__APPLE__)
#define _POSIX_C_SOURCE 200809L /* mkstemp, fdopen, fsync, fchmod: -std=c99 hides them */
#define RUGO_BAKED_POSIX 1
#endif

#include "rugo/baked.h"

#include "core/internal.h"
#include "shape/internal.h" /* rugo__baked_detail, rugo__baked_clear_detail */

#include <stdio.h>
#include <stdlib.h> /* mkstemp */
#include <string.h>

#ifdef RUGO_BAKED_POSIX
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

/* Writes all of data through the hook (if any) and stdio; 0 on success. */
static int write_all(FILE* fp, const unsigned char* data, size_t size, const rugo_baked_write_hook* hook) {
    const size_t chunk = (size_t)1 << 16;
    while (size > 0) {
        size_t n = size < chunk ? size : chunk;
        size_t ok = n;
        if (hook != NULL && hook->write != NULL) {
            ok = hook->write(data, n, hook->ctx);
            if (ok > n) ok = n;
        }
        if (ok > 0 && fwrite(data, 1, ok, fp) != ok) return -1;
        if (ok < n) return -1;
        data += n;
        size -= n;
    }
    return 0;
}

rugo_status rugo_shape_write_baked_file(const rugo_shape* shape, const char* path,
                                        const rugo_allocator* allocator, const rugo_baked_write_hook* hook,
                                        rugo_baked_error* detail) {
    rugo__baked_clear_detail(detail);
    if (shape == NULL || path == NULL) {
        rugo__baked_detail(detail, 0, NULL, "NULL shape or path");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    const rugo_allocator al = rugo__allocator_or_default(allocator);
    size_t size = 0;
    rugo_status st = rugo_shape_bake_size(shape, &size);
    if (st != RUGO_OK) {
        rugo__baked_detail(detail, 0, NULL, "the shape needs %lu bytes, beyond the limit",
                           (unsigned long)size);
        return st;
    }
    unsigned char* bytes = (unsigned char*)rugo__alloc_array(&al, size, 1);
    const size_t plen = strlen(path);
    char* tmp = (char*)rugo__alloc_array(&al, plen + 16, 1);
    if (bytes == NULL || tmp == NULL) {
        rugo__free(&al, bytes);
        rugo__free(&al, tmp);
        rugo__baked_detail(detail, 0, NULL, "cannot allocate %lu bytes", (unsigned long)size);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    size_t written = 0;
    st = rugo_shape_bake(shape, bytes, size, &written);
    RUGO_ASSERT(st == RUGO_OK && written == size);
    memcpy(tmp, path, plen);
    const char* step = NULL;
    FILE* fp = NULL;
    int have_tmp = 0;
#ifdef RUGO_BAKED_POSIX
    /* A unique name next to the destination, so that rename() stays on one file system. */
    memcpy(tmp + plen, ".tmp-XXXXXX", 12);
    const int fd = mkstemp(tmp);
    if (fd < 0) {
        step = "cannot create a temporary file in the destination directory";
    } else {
        have_tmp = 1;
        (void)fchmod(fd, 0644); /* mkstemp makes 0600; a baked asset is meant to be shared */
        fp = fdopen(fd, "wb");
        if (fp == NULL) {
            close(fd);
            step = "cannot open the temporary file";
        }
    }
#else
    memcpy(tmp + plen, ".tmp", 5);
    fp = fopen(tmp, "wb");
    if (fp == NULL)
        step = "cannot create a temporary file in the destination directory";
    else
        have_tmp = 1;
#endif
    if (step == NULL && write_all(fp, bytes, size, hook) != 0) step = "write failed (disk full?)";
    if (step == NULL && fflush(fp) != 0) step = "flush failed";
#ifdef RUGO_BAKED_POSIX
    if (step == NULL && fsync(fileno(fp)) != 0) step = "fsync failed";
#endif
    if (fp != NULL && fclose(fp) != 0 && step == NULL) step = "close failed";
    if (step == NULL && rename(tmp, path) != 0) {
#ifndef RUGO_BAKED_POSIX
        /* Windows' rename does not replace: remove first (not atomic there). */
        if (remove(path) != 0 || rename(tmp, path) != 0)
#endif
            step = "cannot rename the temporary file over the destination";
    }
    if (step != NULL) {
        if (have_tmp) (void)remove(tmp); /* the destination was never touched */
        rugo__baked_detail(detail, 0, path, "%s", step);
        rugo__free(&al, bytes);
        rugo__free(&al, tmp);
        return RUGO_ERR_IO;
    }
#ifdef RUGO_BAKED_POSIX
    {
        /* Make the rename itself durable: fsync the directory (best effort; not all systems allow it). */
        size_t cut = plen;
        while (cut > 0 && path[cut - 1] != '/')
            --cut;
        if (cut == 0) {
            tmp[0] = '.';
            tmp[1] = '\0';
        } else {
            memcpy(tmp, path, cut);
            tmp[cut] = '\0';
        }
        const int dfd = open(tmp, O_RDONLY);
        if (dfd >= 0) {
            (void)fsync(dfd);
            close(dfd);
        }
    }
#endif
    rugo__free(&al, bytes);
    rugo__free(&al, tmp);
    return RUGO_OK;
}

rugo_status rugo_shape_read_baked_file(const char* path, const rugo_allocator* allocator, rugo_shape** out,
                                       rugo_baked_error* detail) {
    rugo__baked_clear_detail(detail);
    if (out != NULL) *out = NULL;
    if (path == NULL || out == NULL) {
        rugo__baked_detail(detail, 0, NULL, "NULL path or output");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    const rugo_allocator al = rugo__allocator_or_default(allocator);
    FILE* fp = fopen(path, "rb");
    if (fp == NULL) {
        rugo__baked_detail(detail, 0, path, "cannot open");
        return RUGO_ERR_IO;
    }
    /* Grow a buffer chunk by chunk (works for pipes too), never beyond the limit plus one byte: that
     * byte tells a file at the limit from a larger one. */
    const size_t most = RUGO_MAX_BAKED_BYTES + 1;
    size_t cap = 0, len = 0;
    unsigned char* buf = NULL;
    rugo_status st = RUGO_OK;
    for (;;) {
        if (len == cap) {
            if (cap == most) {
                rugo__baked_detail(detail, cap, path, "larger than the limit of %lu bytes",
                                   (unsigned long)RUGO_MAX_BAKED_BYTES);
                st = RUGO_ERR_TOO_LARGE;
                break;
            }
            const size_t ncap = cap == 0 ? (size_t)1 << 16 : (2 * cap < most ? 2 * cap : most);
            unsigned char* nb = (unsigned char*)rugo__alloc_array(&al, ncap, 1);
            if (nb == NULL) {
                rugo__baked_detail(detail, 0, path, "cannot allocate %lu bytes", (unsigned long)ncap);
                st = RUGO_ERR_OUT_OF_MEMORY;
                break;
            }
            if (len > 0) memcpy(nb, buf, len);
            rugo__free(&al, buf);
            buf = nb;
            cap = ncap;
        }
        const size_t got = fread(buf + len, 1, cap - len, fp);
        len += got;
        if (got == 0) {
            if (ferror(fp)) {
                rugo__baked_detail(detail, len, path, "read error");
                st = RUGO_ERR_IO;
            }
            break;
        }
    }
    fclose(fp);
    if (st == RUGO_OK) st = rugo_shape_load_baked(buf, len, &al, out, detail);
    rugo__free(&al, buf);
    return st;
}
