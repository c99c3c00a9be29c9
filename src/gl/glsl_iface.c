#include "gl/glsl_iface.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* ---- macros --------------------------------------------------------------- */

typedef struct macro {
    char name[64];
    char *value;        /* object-like: replacement text */
    bool function_like;
} macro;

typedef struct macros {
    macro *m;
    int n, cap;
} macros;

static macro *find_macro(const macros *t, const char *name, size_t len)
{
    for (int i = t->n - 1; i >= 0; i--) {
        if (strlen(t->m[i].name) == len && !strncmp(t->m[i].name, name, len))
            return &t->m[i];
    }
    return NULL;
}

static void undefine(macros *t, const char *name, size_t len)
{
    macro *m = find_macro(t, name, len);
    if (!m)
        return;
    free(m->value);
    *m = t->m[--t->n];
}

static void define(macros *t, const char *name, size_t len, const char *value, size_t vlen,
                   bool function_like)
{
    if (len >= sizeof(t->m[0].name))
        return;
    undefine(t, name, len);
    if (t->n == t->cap) {
        int cap = t->cap ? 2 * t->cap : 64;
        macro *m = realloc(t->m, (size_t)cap * sizeof(*m));
        if (!m)
            return;
        t->m = m;
        t->cap = cap;
    }
    macro *m = &t->m[t->n];
    memcpy(m->name, name, len);
    m->name[len] = '\0';
    m->value = malloc(vlen + 1);
    if (!m->value)
        return;
    memcpy(m->value, value, vlen);
    m->value[vlen] = '\0';
    m->function_like = function_like;
    t->n++;
}

/* ---- #if expressions ------------------------------------------------------ */

typedef struct val {
    long long v;
    bool known;
} val;

typedef struct expr {
    const char *p;
    const macros *mac;
    int depth;
} expr;

static val eval_text(const macros *mac, const char *text, int depth);

static void skip_space(expr *e)
{
    while (*e->p && isspace((unsigned char)*e->p))
        e->p++;
}

static bool ident_start(char c)
{
    return isalpha((unsigned char)c) || c == '_';
}

static bool ident_char(char c)
{
    return isalnum((unsigned char)c) || c == '_';
}

/* Consumes operator `op` when it comes next (and is not the start of a
 * longer one given in `not_followed`). */
static bool take(expr *e, const char *op, char not_followed)
{
    skip_space(e);
    size_t n = strlen(op);
    if (strncmp(e->p, op, n) != 0 || (not_followed && e->p[n] == not_followed))
        return false;
    e->p += n;
    return true;
}

static val cond_or(expr *e);

static val primary(expr *e)
{
    skip_space(e);
    if (take(e, "(", 0)) {
        val v = cond_or(e);
        if (!take(e, ")", 0))
            v.known = false;
        return v;
    }
    if (isdigit((unsigned char)*e->p)) {
        char *end;
        long long v = strtoll(e->p, &end, 0);
        e->p = end;
        while (*e->p == 'u' || *e->p == 'U' || *e->p == 'l' || *e->p == 'L')
            e->p++;
        return (val){v, true};
    }
    if (ident_start(*e->p)) {
        const char *s = e->p;
        while (ident_char(*e->p))
            e->p++;
        size_t len = (size_t)(e->p - s);
        if (len == 7 && !strncmp(s, "defined", 7)) {
            bool paren = take(e, "(", 0);
            skip_space(e);
            const char *n = e->p;
            while (ident_char(*e->p))
                e->p++;
            if (paren && !take(e, ")", 0))
                return (val){0, false};
            return (val){find_macro(e->mac, n, (size_t)(e->p - n)) != NULL, true};
        }
        const macro *m = find_macro(e->mac, s, len);
        if (!m)
            return (val){0, true}; /* C: an unknown identifier is 0 */
        if (m->function_like || e->depth > 16) {
            /* skip a call's arguments: the value stays unknown */
            skip_space(e);
            if (*e->p == '(') {
                int level = 0;
                do {
                    level += *e->p == '(';
                    level -= *e->p == ')';
                    e->p++;
                } while (*e->p && level > 0);
            }
            return (val){0, false};
        }
        return eval_text(e->mac, m->value, e->depth + 1);
    }
    return (val){0, false};
}

static val unary(expr *e)
{
    if (take(e, "!", '='))
        { val v = unary(e); return (val){!v.v, v.known}; }
    if (take(e, "~", 0))
        { val v = unary(e); return (val){~v.v, v.known}; }
    if (take(e, "-", 0))
        { val v = unary(e); return (val){-v.v, v.known}; }
    if (take(e, "+", 0))
        return unary(e);
    return primary(e);
}

static val binop(val a, val b, char op)
{
    val r = {0, a.known && b.known};
    switch (op) {
    case '*': r.v = a.v * b.v; break;
    case '/': if (b.v) r.v = a.v / b.v; else r.known = false; break;
    case '%': if (b.v) r.v = a.v % b.v; else r.known = false; break;
    case '+': r.v = a.v + b.v; break;
    case '-': r.v = a.v - b.v; break;
    case 'l': r.v = a.v << (b.v & 63); break;
    case 'r': r.v = a.v >> (b.v & 63); break;
    case '<': r.v = a.v < b.v; break;
    case '>': r.v = a.v > b.v; break;
    case 'L': r.v = a.v <= b.v; break;
    case 'G': r.v = a.v >= b.v; break;
    case '=': r.v = a.v == b.v; break;
    case '!': r.v = a.v != b.v; break;
    case '&': r.v = a.v & b.v; break;
    case '^': r.v = a.v ^ b.v; break;
    case '|': r.v = a.v | b.v; break;
    default: r.known = false;
    }
    return r;
}

/* The binary operators by precedence, tightest first: each level's
 * operators (text, the character that must not follow it, binop's code). */
typedef struct {
    const char *text;
    char not_followed, code;
} binary_op;

static const binary_op binary_levels[][5] = {
    {{"*", 0, '*'}, {"/", 0, '/'}, {"%", 0, '%'}},
    {{"+", 0, '+'}, {"-", 0, '-'}},
    {{"<<", 0, 'l'}, {">>", 0, 'r'}},
    {{"<=", 0, 'L'}, {">=", 0, 'G'}, {"<", '<', '<'}, {">", '>', '>'}},
    {{"==", 0, '='}, {"!=", 0, '!'}},
    {{"&", '&', '&'}},
    {{"^", 0, '^'}},
    {{"|", '|', '|'}},
};

#define NUM_BINARY_LEVELS ((int)(sizeof(binary_levels) / sizeof(binary_levels[0])))

/* The operators of `level` and tighter, left to right; level -1 is unary. */
static val binary(expr *e, int level)
{
    if (level < 0)
        return unary(e);
    val a = binary(e, level - 1);
    for (;;) {
        char op = 0;
        for (const binary_op *o = binary_levels[level]; !op && o->text; o++)
            if (take(e, o->text, o->not_followed))
                op = o->code;
        if (!op)
            return a;
        a = binop(a, binary(e, level - 1), op);
    }
}

/* && and ||: a known false (true) operand decides even beside an unknown. */
static val logic_and(expr *e)
{
    val a = binary(e, NUM_BINARY_LEVELS - 1);
    while (take(e, "&&", 0)) {
        val b = binary(e, NUM_BINARY_LEVELS - 1);
        bool f = (a.known && !a.v) || (b.known && !b.v);
        a = f ? (val){0, true} : (val){1, a.known && b.known};
    }
    return a;
}

static val cond_or(expr *e)
{
    val a = logic_and(e);
    while (take(e, "||", 0)) {
        val b = logic_and(e);
        bool t = (a.known && a.v) || (b.known && b.v);
        a = t ? (val){1, true} : (val){0, a.known && b.known};
    }
    if (take(e, "?", 0))
        a.known = false; /* not needed by the shaders: unknown */
    return a;
}

static val eval_text(const macros *mac, const char *text, int depth)
{
    expr e = {text, mac, depth};
    val v = cond_or(&e);
    skip_space(&e);
    if (*e.p)
        v.known = false; /* something left it did not understand */
    return v;
}

/* ---- conditional regions -------------------------------------------------- */

enum { NO = 0, YES = 1, MAYBE = 2 };

static int tri_and(int a, int b)
{
    if (a == NO || b == NO)
        return NO;
    return a == YES && b == YES ? YES : MAYBE;
}

static int tri_not(int a)
{
    return a == MAYBE ? MAYBE : !a;
}

static int tri_or(int a, int b)
{
    if (a == YES || b == YES)
        return YES;
    return a == NO && b == NO ? NO : MAYBE;
}

static int tri_of(val v)
{
    return !v.known ? MAYBE : v.v ? YES : NO;
}

typedef struct cond {
    int parent, state, taken;
} cond;

/* ---- tokens and declarations ---------------------------------------------- */

typedef struct tok {
    const char *s;
    int len;
} tok;

static bool tok_is(tok t, const char *w)
{
    return (int)strlen(w) == t.len && !strncmp(t.s, w, (size_t)t.len);
}

static bool is_image_type(tok t)
{
    const char *s = t.s;
    int n = t.len;
    if (n > 6 && (*s == 'i' || *s == 'u') && !strncmp(s + 1, "image", 5))
        return true; /* iimage*, uimage* */
    return n > 5 && !strncmp(s, "image", 5);
}

/* Memory qualifier bits of the tokens [from, to), macros expanded. */
static int qualifiers(const macros *mac, const tok *t, int from, int to, int depth)
{
    int q = 0;
    for (int i = from; i < to; i++) {
        if (tok_is(t[i], "readonly"))
            q |= 1;
        else if (tok_is(t[i], "writeonly"))
            q |= 2;
        else if (tok_is(t[i], "uniform"))
            q |= 4;
        else if (depth < 8 && ident_start(*t[i].s)) {
            const macro *m = find_macro(mac, t[i].s, (size_t)t[i].len);
            if (m && !m->function_like) {
                /* tokenize the replacement */
                tok sub[16];
                int n = 0;
                for (const char *p = m->value; *p && n < 16;) {
                    if (ident_start(*p)) {
                        const char *s = p;
                        while (ident_char(*p))
                            p++;
                        sub[n++] = (tok){s, (int)(p - s)};
                    } else {
                        p++;
                    }
                }
                q |= qualifiers(mac, sub, 0, n, depth + 1);
            }
        }
    }
    return q;
}

static void add_decl(glsl_decl *out, int max, int *n, const tok name, bool image, int q)
{
    enum glsl_access a = (q & 3) == 1 ? GLSL_READ : (q & 3) == 2 ? GLSL_WRITE : GLSL_READ_WRITE;
    if (name.len <= 0 || name.len >= (int)sizeof(out[0].name))
        return;
    for (int i = 0; i < *n && i < max; i++) {
        if (tok_is(name, out[i].name) && out[i].image == image) {
            out[i].access |= a;
            return;
        }
    }
    if (*n < max) {
        memcpy(out[*n].name, name.s, (size_t)name.len);
        out[*n].name[name.len] = '\0';
        out[*n].image = image;
        out[*n].access = a;
    }
    (*n)++;
}

/* Tokens of the statement being read (since the last ';', '{' or '}'). */
typedef struct scan {
    tok *t;
    int n, cap;
} scan;

static void push_tok(scan *s, tok t)
{
    if (s->n == s->cap) {
        int cap = s->cap ? 2 * s->cap : 256;
        tok *nt = realloc(s->t, (size_t)cap * sizeof(*nt));
        if (!nt)
            return;
        s->t = nt;
        s->cap = cap;
    }
    s->t[s->n++] = t;
}

/* A finished statement head t[0..n) that ended with `end`: a storage
 * block ("... buffer Name {") or an image uniform ("... uniform ...
 * image2D name ;"). */
static void statement(const macros *mac, const tok *t, int n, char end, glsl_decl *out,
                      int max, int *count)
{
    if (end == '{' && n >= 2 && tok_is(t[n - 2], "buffer") && ident_start(*t[n - 1].s)) {
        add_decl(out, max, count, t[n - 1], false, qualifiers(mac, t, 0, n - 2, 0));
        return;
    }
    if (end != ';')
        return;
    for (int j = 0; j + 1 < n; j++) {
        if (is_image_type(t[j]) && ident_start(*t[j + 1].s)) {
            int q = qualifiers(mac, t, 0, j, 0);
            if (q & 4)
                add_decl(out, max, count, t[j + 1], true, q);
            return;
        }
    }
}

/* Reads the tokens of [p, end) into the statement, finishing statements. */
static void tokenize(scan *s, const macros *mac, const char *p, const char *end,
                     glsl_decl *out, int max, int *count)
{
    while (p < end) {
        if (isspace((unsigned char)*p)) {
            p++;
        } else if (ident_char(*p)) {
            const char *b = p;
            while (p < end && (ident_char(*p) || *p == '.'))
                p++;
            push_tok(s, (tok){b, (int)(p - b)});
        } else if (*p == ';' || *p == '{' || *p == '}') {
            statement(mac, s->t, s->n, *p, out, max, count);
            s->n = 0;
            p++;
        } else {
            push_tok(s, (tok){p, 1});
            p++;
        }
    }
}

int glsl_memory_decls(const char *text, glsl_decl *out, int max)
{
    if (!text)
        return -1;
    /* Comments out, continuation lines joined (newlines kept). */
    size_t len = strlen(text);
    char *c = malloc(len + 1);
    if (!c)
        return -1;
    size_t k = 0;
    for (size_t i = 0; i < len;) {
        if (text[i] == '/' && text[i + 1] == '/') {
            while (i < len && text[i] != '\n')
                i++;
        } else if (text[i] == '/' && text[i + 1] == '*') {
            i += 2;
            while (i < len && !(text[i] == '*' && text[i + 1] == '/'))
                c[k++] = text[i++] == '\n' ? '\n' : ' ';
            i += 2;
        } else if (text[i] == '\\' && text[i + 1] == '\n') {
            i += 2;
        } else {
            c[k++] = text[i++];
        }
    }
    c[k] = '\0';

    int count = 0;
    macros mac = {0};
    cond stack[64];
    int depth = 0;
    int state = YES;
    scan sc = {0};
    for (char *line = c; *line;) {
        char *eol = strchr(line, '\n');
        char *next = eol ? eol + 1 : line + strlen(line);
        char *p = line;
        while (p < next && (*p == ' ' || *p == '\t'))
            p++;
        if (*p == '#') {
            if (eol)
                *eol = '\0';
            p++;
            while (*p == ' ' || *p == '\t')
                p++;
            const char *d = p;
            while (ident_char(*p))
                p++;
            size_t dl = (size_t)(p - d);
            while (*p == ' ' || *p == '\t')
                p++;
            const char *arg = p;
            const char *n = arg;
            while (ident_char(*n))
                n++;
            size_t nl = (size_t)(n - arg);
#define DIRECTIVE(w) (dl == strlen(w) && !strncmp(d, w, dl))
            if (DIRECTIVE("ifdef") || DIRECTIVE("ifndef") || DIRECTIVE("if")) {
                int v;
                if (DIRECTIVE("if"))
                    v = tri_of(eval_text(&mac, arg, 0));
                else
                    v = (find_macro(&mac, arg, nl) != NULL) == DIRECTIVE("ifdef") ? YES : NO;
                if (depth < 64)
                    stack[depth++] = (cond){state, tri_and(state, v), v};
                state = tri_and(state, v);
            } else if (DIRECTIVE("elif") && depth > 0) {
                cond *t = &stack[depth - 1];
                int v = tri_of(eval_text(&mac, arg, 0));
                t->state = tri_and(t->parent, tri_and(tri_not(t->taken), v));
                t->taken = tri_or(t->taken, v);
                state = t->state;
            } else if (DIRECTIVE("else") && depth > 0) {
                cond *t = &stack[depth - 1];
                t->state = tri_and(t->parent, tri_not(t->taken));
                t->taken = YES;
                state = t->state;
            } else if (DIRECTIVE("endif") && depth > 0) {
                state = stack[--depth].parent;
            } else if (DIRECTIVE("define") && state != NO && nl) {
                bool fn = *n == '(';
                const char *v = n;
                if (fn)
                    v = strchr(n, ')') ? strchr(n, ')') + 1 : n + strlen(n);
                while (*v == ' ' || *v == '\t')
                    v++;
                define(&mac, arg, nl, v, strlen(v), fn);
            } else if (DIRECTIVE("undef") && state == YES && nl) {
                undefine(&mac, arg, nl);
            }
#undef DIRECTIVE
        } else if (state != NO) {
            tokenize(&sc, &mac, line, next, out, max, &count);
        }
        line = next;
    }
    free(sc.t);
    for (int i = 0; i < mac.n; i++)
        free(mac.m[i].value);
    free(mac.m);
    free(c);
    return count;
}
