/* SVG documents: a bounded scan for one <path> (by id, or the only one) with its and its ancestors'
 * transforms composed (rugo_svg_find_path), and the import of its outline (rugo_svg_import_outline:
 * scan, path data, sampling in librugo's y-up frame). Not an XML parser: it reads tags, attributes,
 * comments, CDATA, processing instructions and declarations only as far as finding the path needs. */
#include "io/svg_internal.h"

#include "core/internal.h"
#include "curve/internal.h" /* rugo__affine_finite, RUGO__OUTLINE_SAMPLE_DEF_COOKIE */
#include "io/json.h"        /* rugo__json_locate, rugo__json_quote_for_message */

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Position of the first occurrence of the NUL-terminated needle in text[from, length), or length. */
static size_t find_seq(const char* text, size_t from, size_t length, const char* needle) {
    const size_t n = strlen(needle);
    while (from + n <= length) {
        const char* c = (const char*)memchr(text + from, needle[0], length - from - n + 1);
        if (c == NULL) return length;
        size_t at = (size_t)(c - text);
        if (memcmp(c, needle, n) == 0) return at;
        from = at + 1;
    }
    return length;
}

static int starts_with(const char* text, size_t at, size_t length, const char* s) {
    const size_t n = strlen(s);
    return at + n <= length && memcmp(text + at, s, n) == 0;
}

/* UTF-8 bytes of code point cp into out; returns the count. */
static size_t utf8_encode(unsigned long cp, char* out) {
    if (cp < 0x80) {
        out[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | (cp >> 6));
        out[1] = (char)(0x80 | (cp & 0x3F));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | (cp >> 12));
        out[1] = (char)(0x80 | ((cp >> 6) & 0x3F));
        out[2] = (char)(0x80 | (cp & 0x3F));
        return 3;
    }
    out[0] = (char)(0xF0 | (cp >> 18));
    out[1] = (char)(0x80 | ((cp >> 12) & 0x3F));
    out[2] = (char)(0x80 | ((cp >> 6) & 0x3F));
    out[3] = (char)(0x80 | (cp & 0x3F));
    return 4;
}

/* Decodes the entities of an attribute value raw[0, n) into out (room for n + 1 bytes: decoding never
 * lengthens). On a bad entity returns its offset in raw via *bad and 0; 1 on success. */
static int decode_attribute(const char* raw, size_t n, char* out, size_t* out_len, size_t* bad) {
    static const struct {
        const char* name;
        char c;
    } named[] = {{"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"quot", '"'}, {"apos", '\''}};
    size_t w = 0;
    for (size_t i = 0; i < n;) {
        if (raw[i] != '&') {
            out[w++] = raw[i++];
            continue;
        }
        size_t semi = i + 1;
        while (semi < n && semi - i <= 12 && raw[semi] != ';')
            ++semi;
        if (semi >= n || raw[semi] != ';') {
            *bad = i;
            return 0;
        }
        const char* name = raw + i + 1;
        const size_t nl = semi - i - 1;
        int done = 0;
        for (size_t k = 0; k < sizeof named / sizeof named[0] && !done; ++k)
            if (strlen(named[k].name) == nl && memcmp(named[k].name, name, nl) == 0) {
                out[w++] = named[k].c;
                done = 1;
            }
        if (!done && nl >= 2 && name[0] == '#') {
            unsigned long cp = 0;
            const int hex = name[1] == 'x';
            size_t k = hex ? 2 : 1;
            if (k >= nl) {
                *bad = i;
                return 0;
            }
            for (; k < nl; ++k) {
                const char c = name[k];
                unsigned d;
                if (rugo__svg_is_digit(c))
                    d = (unsigned)(c - '0');
                else if (hex && c >= 'a' && c <= 'f')
                    d = (unsigned)(c - 'a' + 10);
                else if (hex && c >= 'A' && c <= 'F')
                    d = (unsigned)(c - 'A' + 10);
                else {
                    *bad = i;
                    return 0;
                }
                cp = cp * (hex ? 16u : 10u) + d;
                if (cp > 0x10FFFF) {
                    *bad = i;
                    return 0;
                }
            }
            if (cp == 0 || (cp >= 0xD800 && cp <= 0xDFFF)) {
                *bad = i;
                return 0;
            }
            w += utf8_encode(cp, out + w);
            done = 1;
        }
        if (!done) {
            *bad = i;
            return 0;
        }
        i = semi + 1;
    }
    out[w] = '\0';
    *out_len = w;
    return 1;
}

/* An attribute value's raw extent in the document. */
typedef struct attr_span {
    size_t off, len;
    int present;
} attr_span;

/* An open element on the scan's stack. */
typedef struct open_element {
    size_t name_off, name_len;
    size_t tag_off;
    attr_span id, transform;
} open_element;

typedef struct doc_scan {
    const char* text;
    size_t length;
    rugo_allocator al;
    rugo_parse_error* err;
} doc_scan;

#if defined(__GNUC__)
__attribute__((format(printf, 5, 6)))
#endif
static rugo_status
doc_fail(const doc_scan* d, rugo_status st, size_t offset, const char* path, const char* fmt, ...) {
    rugo_parse_error* e = d->err;
    if (e == NULL) return st;
    rugo__json_locate(d->text, d->length, offset, &e->line, &e->column);
    snprintf(e->path, sizeof e->path, "%s", path != NULL ? path : "");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->message, sizeof e->message, fmt, ap);
    va_end(ap);
    return st;
}

/* "g#layer1/transform" or "g/transform" for messages (name and id shortened to fit). */
static void element_label(const doc_scan* d, const open_element* el, const char* attr, char* out,
                          size_t size) {
    char name[32], id[40];
    rugo__json_quote_for_message(d->text + el->name_off, el->name_len, name, sizeof name);
    if (el->id.present) {
        rugo__json_quote_for_message(d->text + el->id.off, el->id.len, id, sizeof id);
        snprintf(out, size, "%s#%s/%s", name, id, attr);
    } else {
        snprintf(out, size, "%s/%s", name, attr);
    }
}

/* Decodes an attribute into a new NUL-terminated buffer (*out, *out_len). */
static rugo_status decode_span(const doc_scan* d, const attr_span* a, const char* label, char** out,
                               size_t* out_len) {
    char* buf = (char*)rugo__alloc_array(&d->al, a->len + 1, 1);
    if (buf == NULL) return doc_fail(d, RUGO_ERR_OUT_OF_MEMORY, a->off, label, "out of memory");
    size_t bad = 0;
    if (!decode_attribute(d->text + a->off, a->len, buf, out_len, &bad)) {
        rugo__free(&d->al, buf);
        return doc_fail(
            d, RUGO_ERR_PARSE, a->off + bad, label,
            "unknown or malformed entity (only &lt; &gt; &amp; &quot; &apos; and &#...; are read)");
    }
    *out = buf;
    return RUGO_OK;
}

/* The transform attribute of el composed into *m (m = m * T_el). */
static rugo_status apply_element_transform(const doc_scan* d, const open_element* el, rugo_affine* m) {
    if (!el->transform.present) return RUGO_OK;
    char label[96];
    element_label(d, el, "transform", label, sizeof label);
    char* buf = NULL;
    size_t n = 0;
    rugo_status st = decode_span(d, &el->transform, label, &buf, &n);
    if (st != RUGO_OK) return st;
    rugo__svg_scanner sc;
    sc.text = buf;
    sc.p = buf;
    sc.end = buf + n;
    sc.loc.doc = d->text;
    sc.loc.doc_length = d->length;
    sc.loc.base = el->transform.off;
    sc.loc.exact = n == el->transform.len;
    sc.loc.path = label;
    sc.err = d->err;
    rugo_affine t;
    st = rugo__svg_transform_list(&sc, &t);
    rugo__free(&d->al, buf);
    if (st != RUGO_OK) return st;
    *m = rugo_affine_multiply(*m, t);
    if (!rugo__affine_finite(m))
        return doc_fail(d, RUGO_ERR_NOT_FINITE, el->transform.off, label, "the composed transform overflows");
    return RUGO_OK;
}

/* 1 if the attribute's decoded value equals s. */
static int attribute_equals(const doc_scan* d, const attr_span* a, const char* s, rugo_status* st) {
    const size_t n = strlen(s);
    const char* raw = d->text + a->off;
    if (memchr(raw, '&', a->len) == NULL) return a->len == n && memcmp(raw, s, n) == 0;
    char* buf = NULL;
    size_t len = 0;
    *st = decode_span(d, a, "id", &buf, &len);
    if (*st != RUGO_OK) return 0;
    const int eq = len == n && memcmp(buf, s, n) == 0;
    rugo__free(&d->al, buf);
    return eq;
}

static int local_name_is(const char* name, size_t len, const char* want) {
    const char* colon = NULL;
    for (size_t i = 0; i < len; ++i)
        if (name[i] == ':') colon = name + i;
    const char* local = colon != NULL ? colon + 1 : name;
    const size_t ll = len - (size_t)(local - name);
    return ll == strlen(want) && memcmp(local, want, ll) == 0;
}

static int is_name_char(char c) {
    return !rugo__svg_is_wsp(c) && c != '>' && c != '/' && c != '=' && c != '"' && c != '\'' && c != '<';
}

rugo_status rugo_svg_find_path(const char* text, size_t length, const char* id,
                               const rugo_allocator* allocator, rugo_svg_path_element* out,
                               rugo_parse_error* error) {
    rugo__svg_clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (text == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (length > RUGO_MAX_SVG_BYTES) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message, "document larger than %lu bytes",
                     (unsigned long)RUGO_MAX_SVG_BYTES);
        return RUGO_ERR_TOO_LARGE;
    }
    doc_scan d;
    d.text = text;
    d.length = length;
    d.al = rugo__allocator_or_default(allocator);
    d.err = error;
    open_element* stack = (open_element*)rugo__alloc_array(&d.al, RUGO_SVG_MAX_DEPTH, sizeof *stack);
    if (stack == NULL) return doc_fail(&d, RUGO_ERR_OUT_OF_MEMORY, 0, "", "out of memory");
    int depth = 0;
    rugo_svg_path_element found;
    memset(&found, 0, sizeof found);
    int nfound = 0;
    rugo_status st = RUGO_OK;
    char buf[16];
    size_t p = 0;
    if (length >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
        (unsigned char)text[2] == 0xBF)
        p = 3;
    int done = 0;
    while (!done && st == RUGO_OK) {
        const char* lt = p < length ? (const char*)memchr(text + p, '<', length - p) : NULL;
        if (lt == NULL) break;
        const size_t at = (size_t)(lt - text);
        if (starts_with(text, at, length, "<!--")) {
            const size_t e = find_seq(text, at + 4, length, "-->");
            if (e >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated comment");
                break;
            }
            p = e + 3;
            continue;
        }
        if (starts_with(text, at, length, "<![CDATA[")) {
            const size_t e = find_seq(text, at + 9, length, "]]>");
            if (e >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated CDATA section");
                break;
            }
            p = e + 3;
            continue;
        }
        if (starts_with(text, at, length, "<?")) {
            const size_t e = find_seq(text, at + 2, length, "?>");
            if (e >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated processing instruction");
                break;
            }
            p = e + 2;
            continue;
        }
        if (starts_with(text, at, length, "<!")) {
            /* A DOCTYPE or other declaration: up to the '>' outside quotes and the internal subset. */
            size_t q = at + 2;
            int bracket = 0;
            char quote = 0;
            for (; q < length; ++q) {
                const char c = text[q];
                if (quote) {
                    if (c == quote) quote = 0;
                } else if (c == '"' || c == '\'') {
                    quote = c;
                } else if (c == '[') {
                    ++bracket;
                } else if (c == ']') {
                    if (bracket > 0) --bracket;
                } else if (c == '>' && bracket == 0) {
                    break;
                }
            }
            if (q >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated declaration");
                break;
            }
            p = q + 1;
            continue;
        }
        if (starts_with(text, at, length, "</")) {
            size_t q = at + 2;
            const size_t name = q;
            while (q < length && is_name_char(text[q]))
                ++q;
            const size_t nlen = q - name;
            while (q < length && rugo__svg_is_wsp(text[q]))
                ++q;
            if (nlen == 0 || q >= length || text[q] != '>') {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "malformed end tag");
                break;
            }
            if (depth == 0) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "end tag without a matching start tag");
                break;
            }
            const open_element* top = &stack[depth - 1];
            if (top->name_len != nlen || memcmp(text + top->name_off, text + name, nlen) != 0) {
                char want[40], got[40];
                rugo__json_quote_for_message(text + top->name_off, top->name_len, want, sizeof want);
                rugo__json_quote_for_message(text + name, nlen, got, sizeof got);
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "end tag </%s> does not match <%s>", got, want);
                break;
            }
            --depth;
            p = q + 1;
            continue;
        }
        /* A start tag. */
        open_element el;
        memset(&el, 0, sizeof el);
        el.tag_off = at;
        size_t q = at + 1;
        el.name_off = q;
        while (q < length && is_name_char(text[q]))
            ++q;
        el.name_len = q - el.name_off;
        if (el.name_len == 0) {
            st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "expected an element name after '<', found %s",
                          rugo__svg_describe(text + q, text + length, buf, sizeof buf));
            break;
        }
        attr_span dspan;
        memset(&dspan, 0, sizeof dspan);
        int self_closing = 0;
        while (st == RUGO_OK) {
            while (q < length && rugo__svg_is_wsp(text[q]))
                ++q;
            if (q >= length) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "unterminated tag");
                break;
            }
            if (text[q] == '>') {
                ++q;
                break;
            }
            if (text[q] == '/') {
                if (q + 1 < length && text[q + 1] == '>') {
                    q += 2;
                    self_closing = 1;
                    break;
                }
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected '>' after '/'");
                break;
            }
            const size_t an = q;
            while (q < length && is_name_char(text[q]))
                ++q;
            const size_t alen = q - an;
            if (alen == 0) {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected an attribute name, found %s",
                              rugo__svg_describe(text + q, text + length, buf, sizeof buf));
                break;
            }
            while (q < length && rugo__svg_is_wsp(text[q]))
                ++q;
            if (q >= length || text[q] != '=') {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected '=' after an attribute name, found %s",
                              rugo__svg_describe(text + q, text + length, buf, sizeof buf));
                break;
            }
            ++q;
            while (q < length && rugo__svg_is_wsp(text[q]))
                ++q;
            if (q >= length || (text[q] != '"' && text[q] != '\'')) {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "expected a quoted attribute value, found %s",
                              rugo__svg_describe(text + q, text + length, buf, sizeof buf));
                break;
            }
            const char quote = text[q];
            const size_t vstart = q + 1;
            size_t v = vstart;
            while (v < length && text[v] != quote && text[v] != '<')
                ++v;
            if (v >= length || text[v] != quote) {
                st = doc_fail(&d, RUGO_ERR_PARSE, q, "", "unterminated attribute value");
                break;
            }
            attr_span span;
            span.off = vstart;
            span.len = v - vstart;
            span.present = 1;
            attr_span* slot = NULL;
            if (alen == 2 && memcmp(text + an, "id", 2) == 0)
                slot = &el.id;
            else if (alen == 9 && memcmp(text + an, "transform", 9) == 0)
                slot = &el.transform;
            else if (alen == 1 && text[an] == 'd')
                slot = &dspan;
            if (slot != NULL) {
                if (slot->present) {
                    char name[16];
                    rugo__json_quote_for_message(text + an, alen, name, sizeof name);
                    st = doc_fail(&d, RUGO_ERR_PARSE, an, "", "attribute %s given twice", name);
                    break;
                }
                *slot = span;
            }
            q = v + 1;
        }
        if (st != RUGO_OK) break;
        const int is_path = local_name_is(text + el.name_off, el.name_len, "path");
        int target = 0;
        if (id != NULL) {
            if (el.id.present) target = attribute_equals(&d, &el.id, id, &st);
            if (st != RUGO_OK) break;
        } else {
            target = is_path;
        }
        if (target) {
            char label[96];
            element_label(&d, &el, "d", label, sizeof label);
            if (!is_path) {
                char name[32], shown[40];
                rugo__json_quote_for_message(text + el.name_off, el.name_len, name, sizeof name);
                rugo__json_quote_for_message(id, strlen(id), shown, sizeof shown);
                st = doc_fail(&d, RUGO_ERR_BAD_FIELD, at, "", "the element with id '%s' is <%s>, not <path>",
                              shown, name);
                break;
            }
            if (!dspan.present) {
                st = doc_fail(&d, RUGO_ERR_BAD_FIELD, at, label, "the <path> has no d attribute");
                break;
            }
            if (nfound > 0) {
                int line = 0, col = 0;
                rugo__json_locate(text, length, found.d_offset, &line, &col);
                st = doc_fail(&d, RUGO_ERR_BAD_FIELD, at, "",
                              "the document has more than one <path> (another at line %d): choose one by id",
                              line);
                break;
            }
            rugo_affine m = rugo_affine_identity();
            for (int k = 0; k < depth && st == RUGO_OK; ++k)
                st = apply_element_transform(&d, &stack[k], &m);
            if (st == RUGO_OK) st = apply_element_transform(&d, &el, &m);
            if (st != RUGO_OK) break;
            size_t dlen = 0;
            st = decode_span(&d, &dspan, label, &found.d, &dlen);
            if (st != RUGO_OK) break;
            found.d_length = dlen;
            found.d_offset = dspan.off;
            found.d_has_entities = dlen != dspan.len;
            found.transform = m;
            rugo__json_locate(text, length, at, &found.line, &found.column);
            found.allocator = d.al;
            ++nfound;
            if (id != NULL) done = 1; /* the first element with the id wins; the rest is not read */
        }
        if (!self_closing && !done) {
            if (depth >= RUGO_SVG_MAX_DEPTH) {
                st = doc_fail(&d, RUGO_ERR_PARSE, at, "", "elements nested deeper than %d",
                              RUGO_SVG_MAX_DEPTH);
                break;
            }
            stack[depth++] = el;
        }
        p = q;
    }
    rugo__free(&d.al, stack);
    if (st == RUGO_OK && nfound == 0) {
        if (id != NULL) {
            char shown[64];
            rugo__json_quote_for_message(id, strlen(id), shown, sizeof shown);
            st = doc_fail(&d, RUGO_ERR_BAD_FIELD, length, "", "no element with id '%s'", shown);
        } else {
            st = doc_fail(&d, RUGO_ERR_BAD_FIELD, length, "", "the document has no <path> element");
        }
        if (error != NULL) error->line = error->column = 0;
    }
    if (st != RUGO_OK) {
        rugo_svg_path_element_free(&found);
        return st;
    }
    *out = found;
    return RUGO_OK;
}

void rugo_svg_path_element_free(rugo_svg_path_element* element) {
    if (element == NULL) return;
    rugo__free(&element->allocator, element->d);
    memset(element, 0, sizeof *element);
}

rugo_status rugo_svg_import_outline(const char* text, size_t length, const char* id,
                                    const rugo_outline_sample_def* def, rugo_outline_samples* out,
                                    rugo_parse_error* error) {
    rugo__svg_clear_error(error);
    if (out != NULL) memset(out, 0, sizeof *out);
    if (text == NULL || def == NULL || out == NULL) {
        if (error != NULL) snprintf(error->message, sizeof error->message, "a required argument is NULL");
        return RUGO_ERR_NULL_ARGUMENT;
    }
    if (def->cookie != RUGO__OUTLINE_SAMPLE_DEF_COOKIE) {
        if (error != NULL)
            snprintf(error->message, sizeof error->message, "def not from rugo_default_outline_sample_def");
        return RUGO_ERR_BAD_ARGUMENT;
    }
    rugo_svg_path_element el;
    rugo_status st = rugo_svg_find_path(text, length, id, &def->allocator, &el, error);
    if (st != RUGO_OK) return st;
    char label[96];
    if (id != NULL) {
        char shown[64];
        rugo__json_quote_for_message(id, strlen(id), shown, sizeof shown);
        snprintf(label, sizeof label, "path#%s/d", shown);
    } else {
        snprintf(label, sizeof label, "path/d");
    }
    rugo__svg_locator loc;
    loc.doc = text;
    loc.doc_length = length;
    loc.base = el.d_offset;
    loc.exact = !el.d_has_entities;
    loc.path = label;
    rugo_path path;
    memset(&path, 0, sizeof path);
    st = rugo__svg_path_parse_located(el.d, el.d_length, &def->allocator, &path, error, &loc);
    if (st == RUGO_OK) {
        rugo_outline_sample_def sd = *def;
        sd.path = &path;
        const rugo_affine flip = rugo__svg_affine(1.0, 0.0, 0.0, -1.0, 0.0, 0.0);
        sd.transform = rugo_affine_multiply(def->transform, rugo_affine_multiply(flip, el.transform));
        if (!rugo__affine_finite(&sd.transform)) {
            st = RUGO_ERR_NOT_FINITE;
            if (error != NULL)
                snprintf(error->message, sizeof error->message, "the composed transform overflows");
        } else {
            st = rugo_outline_sample(&sd, out, error);
        }
        if (st != RUGO_OK && error != NULL) {
            /* Sampling errors concern the path as a whole: point at its d attribute. */
            rugo__json_locate(text, length, el.d_offset, &error->line, &error->column);
            snprintf(error->path, sizeof error->path, "%s", label);
        }
    }
    rugo_path_free(&path);
    rugo_svg_path_element_free(&el);
    return st;
}
