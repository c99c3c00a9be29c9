/* DIRT engine: the libFuzzer driver of the scene fuzz target (clang
 * -fsanitize=fuzzer,address,undefined; built with -Dfuzz=true). Run:
 *   fuzz_replay --write corpus && fuzz_scene corpus -max_total_time=60 */
#include "fuzz_scene.h"

#include "dirt/log.h"

#include <stdlib.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void quiet(void *user, enum dirt_log_level level, const char *file, int line,
                  const char *msg)
{
    (void)user, (void)level, (void)file, (void)line, (void)msg;
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    dirt_log_set_callback(quiet, NULL);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!dirt_fuzz_scene_one(data, size))
        abort(); /* an invariant broke: libFuzzer saves the input */
    return 0;
}
