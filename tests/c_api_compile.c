/* The public header compiled as C99 with -Wall -Wextra -pedantic, every struct used, and a few
 * calls that need no GL context. Returns 0 when every check passes; prints the failures otherwise.
 * The offsets the (C++) library reports in its settings table are compared with the offsets this C
 * compiler computes, so a layout difference between C and C++ would fail here. */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "obscura/obscura.h"

static int failures = 0;

#define CHECK(cond)                                                   \
    do {                                                              \
        if (!(cond)) {                                                \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            ++failures;                                               \
        }                                                             \
    } while (0)

static void* test_alloc(size_t size, void* user_data) { (void)user_data; (void)size; return NULL; }
static void test_free(void* ptr, void* user_data) { (void)ptr; (void)user_data; }
static void test_log(obscura_log_level level, obscura_status status, const char* message, void* user_data) {
    (void)level; (void)status; (void)message; (void)user_data;
}
static obscura_gl_function test_proc(const char* name) { (void)name; return NULL; }

static size_t table_offset(const char* name) {
    const obscura_setting_info* infos = NULL;
    uint32_t count = 0, i;
    if (obscura_get_setting_infos(OBSCURA_METHOD_HBAO, &infos, &count) != OBSCURA_OK) return (size_t)-1;
    for (i = 0; i < count; ++i)
        if (strcmp(infos[i].name, name) == 0) return infos[i].offset;
    return (size_t)-1;
}

int main(void) {
    obscura_allocator allocator = {0};
    obscura_context_desc desc = {0};
    obscura_hbao_settings hbao = {0};
    obscura_settings settings = {0};
    obscura_setting_info info = {0};
    obscura_rect rect = {0, 0, 0, 0};
    obscura_input input = {0};
    obscura_output output = {0};
    obscura_timing timing = {0};
    obscura_context* context = NULL;
    obscura_log_fn log_fn = test_log;
    obscura_get_proc_address_fn proc_fn = test_proc;
    obscura_status status;
    double value = 0.0;
    const char* text;

    allocator.alloc = test_alloc;
    allocator.free = test_free;
    desc.struct_size = sizeof desc;
    desc.header_version = OBSCURA_VERSION;
    desc.get_proc_address = proc_fn;
    desc.allocator = allocator;
    desc.log = log_fn;
    desc.flags = OBSCURA_CONTEXT_FLAG_SYNC_TIMING | OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES;
    hbao.radius = 1.5f;
    hbao.blur = OBSCURA_TOGGLE_OFF;
    settings.struct_size = sizeof settings;
    settings.method = OBSCURA_METHOD_HBAO;
    settings.hbao = hbao;
    info.type = OBSCURA_SETTING_TOGGLE;
    rect.width = 4;
    input.struct_size = sizeof input;
    input.depth_kind = OBSCURA_DEPTH_LINEAR_VIEW;
    input.output_rect = rect;
    input.projection_layout = OBSCURA_MATRIX_ROW_MAJOR;
    input.clip_depth = OBSCURA_CLIP_DEPTH_ZERO_TO_ONE;
    output.struct_size = sizeof output;
    output.blend = OBSCURA_BLEND_MULTIPLY;
    output.debug_view = OBSCURA_DEBUG_AO_BEFORE_BLUR;
    timing.milliseconds = 0.0;
    CHECK(info.type == OBSCURA_SETTING_TOGGLE && rect.width == 4 && timing.label == NULL);
    CHECK(input.output_rect.width == 4 && output.blend == OBSCURA_BLEND_MULTIPLY);

    CHECK(obscura_version() == OBSCURA_VERSION);

    status = obscura_default_settings(OBSCURA_METHOD_HBAO, &settings);
    CHECK(status == OBSCURA_OK);
    CHECK(settings.struct_size == sizeof settings);
    CHECK(settings.hbao.directions == 8 && settings.hbao.steps == 7);
    CHECK(obscura_set_setting(&settings, "radius", 2.0) == OBSCURA_OK);
    CHECK(obscura_get_setting(&settings, "radius", &value) == OBSCURA_OK && value == 2.0);
    CHECK(obscura_set_setting(&settings, "no_such", 1.0) == OBSCURA_STATUS_UNKNOWN_SETTING);

    text = obscura_status_string(OBSCURA_STATUS_INVALID_SETTING);
    CHECK(text != NULL && strncmp(text, "OBSCURA_STATUS_INVALID_SETTING", 30) == 0);
    text = obscura_status_string(OBSCURA_STATUS_COUNT_);
    CHECK(text != NULL && text[0] != '\0');
    CHECK(strcmp(obscura_method_name(OBSCURA_METHOD_HBAO), "hbao") == 0);

    /* Layout agreement between this C compiler and the C++ library. */
    CHECK(table_offset("radius") == offsetof(obscura_settings, hbao) + offsetof(obscura_hbao_settings, radius));
    CHECK(table_offset("blur") == offsetof(obscura_settings, hbao) + offsetof(obscura_hbao_settings, blur));
    CHECK(table_offset("blur_sharpness") ==
          offsetof(obscura_settings, hbao) + offsetof(obscura_hbao_settings, blur_sharpness));

    /* No GL here: creation fails cleanly (the loader returns NULL for everything). */
    status = obscura_create_context(&desc, &context);
    CHECK(status != OBSCURA_OK && context == NULL);
    desc.header_version = 10000u + OBSCURA_VERSION;
    CHECK(obscura_create_context(&desc, &context) == OBSCURA_STATUS_VERSION_MISMATCH);

    /* Any int a C host passes for an enum: answered, never undefined (found by the settings fuzzer under
       UBSan's enum check, which the sanitizer builds run this program with). */
    {
        const int raw[] = {-1, 100, (int)OBSCURA_STATUS_COUNT_, (int)OBSCURA_METHOD_COUNT_};
        size_t i;
        for (i = 0; i < sizeof raw / sizeof raw[0]; ++i) {
            obscura_settings s;
            const obscura_setting_info* infos = NULL;
            uint32_t count = 0;
            const int method_ok = raw[i] >= 0 && raw[i] < (int)OBSCURA_METHOD_COUNT_;
            CHECK(strncmp(obscura_status_string((obscura_status)raw[i]), "OBSCURA_STATUS_", 15) == 0);
            CHECK((obscura_method_name((obscura_method)raw[i]) != NULL) == method_ok);
            CHECK(obscura_method_available((obscura_method)raw[i]) == method_ok);
            CHECK((obscura_default_settings((obscura_method)raw[i], &s) == OBSCURA_STATUS_INVALID_ENUM) == !method_ok);
            CHECK((obscura_get_setting_infos((obscura_method)raw[i], &infos, &count) == OBSCURA_STATUS_INVALID_ENUM) ==
                  !method_ok);
        }
    }

    if (failures) {
        fprintf(stderr, "%d check(s) failed\n", failures);
        return 1;
    }
    printf("C99 API check passed (%u)\n", (unsigned)obscura_version());
    return 0;
}
