/* Provenance attributes of the programs' outputs (provenance.h). */
#include "app/provenance.h"

#include <stdio.h>
#include <string.h>

#include "dirt/version.h"

size_t app_shell_quote(char *buf, size_t size, size_t len, const char *arg)
{
    bool plain = arg[0] != '\0';
    for (const char *c = arg; *c; c++)
        plain &= (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') ||
                 (*c >= '0' && *c <= '9') || strchr("_./+-,:=%@", *c) != NULL;
    if (len >= size)
        return len;
    if (len)
        len += (size_t)snprintf(buf + len, size - len, " ");
    if (plain) {
        len += (size_t)snprintf(buf + len, len < size ? size - len : 0, "%s", arg);
        return len < size ? len : size;
    }
    /* 'a'\''b': single quotes, each quote closed, escaped and reopened. */
    if (len < size)
        len += (size_t)snprintf(buf + len, size - len, "'");
    for (const char *c = arg; *c && len < size; c++)
        len += (size_t)snprintf(buf + len, size - len, *c == '\'' ? "'\\''" : "%c", *c);
    if (len < size)
        len += (size_t)snprintf(buf + len, size - len, "'");
    return len < size ? len : size;
}

void app_provenance_init(app_provenance *p, int argc, char **argv, const char *scene)
{
    memset(p, 0, sizeof(*p));
    snprintf(p->scene, sizeof(p->scene), "%s", scene ? scene : "default");
    size_t len = 0;
    for (int i = 0; i < argc; i++)
        len = app_shell_quote(p->command_line, sizeof(p->command_line), len, argv[i]);
}

void app_provenance_extra(app_provenance *p, const char *name, const char *value)
{
    snprintf(p->extra_name, sizeof(p->extra_name), "%s", name);
    snprintf(p->extra, sizeof(p->extra), "%s", value);
}

const dirt_image_attr *app_provenance_attrs(app_provenance *p, const dirt_session_stats *st,
                                            bool exr, size_t *count)
{
    snprintf(p->values[0], sizeof(p->values[0]), "%s", dirt_engine_names[st->engine]);
    snprintf(p->values[1], sizeof(p->values[1]), "%u", st->seed);
    snprintf(p->values[2], sizeof(p->values[2]), "%d", st->samples);
    snprintf(p->values[3], sizeof(p->values[3]), "%.17g", st->time);
    snprintf(p->values[4], sizeof(p->values[4]), "%s", st->device);
    static const char *const names[][2] = {
        {"dirt.scene", "scene"}, {"dirt.engine", "engine"}, {"dirt.seed", "seed"},
        {"dirt.samples", "samples"}, {"dirt.time", "time"}, {"dirt.device", "device"},
        {"dirt.command_line", "command_line"}, {"dirt.version", "version"},
        {"dirt.commit", "commit"}};
    const char *values[] = {p->scene, p->values[0], p->values[1], p->values[2], p->values[3],
                            p->values[4], p->command_line, dirt_version(), dirt_version_commit()};
    size_t n = 0;
    for (size_t i = 0; i < sizeof(values) / sizeof(values[0]); i++)
        p->attrs[n++] = (dirt_image_attr){names[i][exr ? 0 : 1], values[i]};
    if (p->extra_name[0]) {
        snprintf(p->values[5], sizeof(p->values[5]), "dirt.%s", p->extra_name);
        p->attrs[n++] = (dirt_image_attr){exr ? p->values[5] : p->extra_name, p->extra};
    }
    *count = n;
    return p->attrs;
}
