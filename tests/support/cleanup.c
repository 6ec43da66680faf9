#include "cleanup.h"
#include "mesh_gen.h"

#include <stdlib.h>

typedef struct entry {
    void *p;
    void (*fn)(void *);
} entry;

static entry *g_entries;
static size_t g_count, g_capacity;

void *cleanup_add(void *p, void (*fn)(void *)) {
    if (!p) return p;
    if (g_count == g_capacity) {
        const size_t cap = g_capacity ? 2 * g_capacity : 16;
        entry *grown = realloc(g_entries, cap * sizeof *grown);
        if (!grown) abort();
        g_entries = grown;
        g_capacity = cap;
    }
    g_entries[g_count].p = p;
    g_entries[g_count].fn = fn;
    ++g_count;
    return p;
}

void *cleanup_calloc(size_t bytes) {
    void *p = calloc(bytes ? bytes : 1, 1);
    if (!p) abort();
    return cleanup_add(p, free);
}

void cleanup_free_test_mesh(void *mesh) {
    tm_free(mesh);
    free(mesh);
}

int cleanup_teardown(void **state) {
    (void)state;
    while (g_count > 0) {
        --g_count;
        g_entries[g_count].fn(g_entries[g_count].p);
    }
    free(g_entries);
    g_entries = NULL;
    g_capacity = 0;
    return 0;
}
