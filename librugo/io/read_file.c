/* Whole files read into text (rugo_read_file), bounded by RUGO_MAX_JSON_BYTES, and the texts io hands
 * out freed (rugo_text_free). */
#include "rugo/shape_file.h"

#include "core/internal.h"

#include <stdio.h>
#include <string.h>

void rugo_text_free(rugo_text* text) {
    if (text == NULL) return;
    rugo__free(&text->allocator, text->data);
    memset(text, 0, sizeof *text);
}

rugo_status rugo_read_file(const char* path, const rugo_allocator* allocator, rugo_text* out) {
    if (out != NULL) memset(out, 0, sizeof *out);
    if (path == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    FILE* f = fopen(path, "rb");
    if (f == NULL) return RUGO_ERR_IO;

    /* The size, when the file can tell it, refuses a huge file before reading it and sizes the buffer;
     * pipes and special files cannot, and are read in growing chunks. */
    const size_t limit = RUGO_MAX_JSON_BYTES;
    size_t cap = 1 << 16;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n >= 0 && (unsigned long)n > (unsigned long)limit) {
            /* Some file systems report a huge size for a directory: tell that apart by reading. */
            rugo_status s = RUGO_ERR_PARSE;
            if (fseek(f, 0, SEEK_SET) != 0 || (fgetc(f) == EOF && ferror(f))) s = RUGO_ERR_IO;
            fclose(f);
            return s;
        }
        if (n >= 0) cap = (size_t)n + 1;
        if (fseek(f, 0, SEEK_SET) != 0) {
            fclose(f);
            return RUGO_ERR_IO;
        }
    }
    clearerr(f);

    char* buf = (char*)rugo__alloc_array(allocator, cap, 1);
    size_t len = 0;
    rugo_status s = RUGO_OK;
    if (buf == NULL) s = RUGO_ERR_OUT_OF_MEMORY;
    while (s == RUGO_OK) {
        if (len + 1 == cap) {
            /* Full (one byte stays for the NUL). A file whose size was known usually ends here: look
             * for one more byte before growing. */
            int c = fgetc(f);
            if (c == EOF) {
                if (ferror(f)) s = RUGO_ERR_IO;
                break;
            }
            if (len >= limit) {
                s = RUGO_ERR_PARSE;
                break;
            }
            size_t ncap = cap * 2;
            if (ncap > limit + 1) ncap = limit + 1;
            char* nbuf = (char*)rugo__alloc_array(allocator, ncap, 1);
            if (nbuf == NULL) {
                s = RUGO_ERR_OUT_OF_MEMORY;
                break;
            }
            memcpy(nbuf, buf, len);
            rugo__free(allocator, buf);
            buf = nbuf;
            cap = ncap;
            buf[len++] = (char)c;
            continue;
        }
        size_t got = fread(buf + len, 1, cap - 1 - len, f);
        len += got;
        if (got == 0) {
            if (ferror(f)) s = RUGO_ERR_IO;
            break;
        }
    }
    if (s == RUGO_OK && len > limit) s = RUGO_ERR_PARSE;
    fclose(f);
    if (s != RUGO_OK) {
        rugo__free(allocator, buf);
        return s;
    }
    buf[len] = '\0';
    out->data = buf;
    out->length = len;
    out->allocator = rugo__allocator_or_default(allocator);
    return RUGO_OK;
}
