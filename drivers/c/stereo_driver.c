/* stereo_driver.c: see stereo_driver.h. C99, no library calls. */
#include "stereo_driver.h"

#include "stereo_regs.h"

#define STEREO_KERNEL_SUM 256

static uint32_t field_max(uint32_t mask, int lsb) {
    return mask >> lsb;
}

int stereo_probe(const stereo_device* dev, stereo_build* build) {
    uint32_t size;
    uint32_t word;
    if (dev->read(dev->context, STEREO_REG_ID) != STEREO_REGMAP_ID) {
        return STEREO_E_ID;
    }
    build->version = dev->read(dev->context, STEREO_REG_VERSION);
    if (STEREO_REGMAP_VERSION_MAJOR(build->version) !=
        STEREO_REGMAP_VERSION_MAJOR(STEREO_REGMAP_VERSION)) {
        return STEREO_E_VERSION;
    }
    size = dev->read(dev->context, STEREO_REG_MAX_SIZE);
    build->max_width = (int)STEREO_GET(STEREO_MAX_SIZE_WIDTH, size);
    build->max_height = (int)STEREO_GET(STEREO_MAX_SIZE_HEIGHT, size);
    word = dev->read(dev->context, STEREO_REG_BUILD);
    build->ndisp = (int)STEREO_GET(STEREO_BUILD_NDISP, word);
    build->window = 2 * (int)STEREO_GET(STEREO_BUILD_RADIUS, word) + 1;
    build->max_min_disp = (int)STEREO_GET(STEREO_BUILD_MAX_MIN_DISP, word);
    build->runtime_kernel = (int)STEREO_GET(STEREO_BUILD_RUNTIME_KERNEL, word);
    build->cost = (int)STEREO_GET(STEREO_BUILD_COST, word);
    return STEREO_OK;
}

/* 1 when lo <= value <= hi. */
static int within(int value, int lo, int hi) {
    return value >= lo && value <= hi;
}

static int check_kernel(const stereo_build* build, const stereo_config* config) {
    int i;
    int sum = 0;
    if (config->kernel == 0) {
        return (build->runtime_kernel || config->window == build->window) ? STEREO_OK
                                                                          : STEREO_E_KERNEL;
    }
    if (!build->runtime_kernel) {
        return STEREO_E_KERNEL;
    }
    for (i = 0; i < config->window; ++i) {
        if (config->kernel[i] > field_max(STEREO_KERNEL_TAP_MASK, STEREO_KERNEL_TAP_LSB)) {
            return STEREO_E_KERNEL;
        }
        sum += config->kernel[i];
    }
    return sum == STEREO_KERNEL_SUM ? STEREO_OK : STEREO_E_KERNEL;
}

int stereo_configure(const stereo_device* dev, const stereo_build* build,
                     const stereo_config* config) {
    const int uniqueness_max =
        (int)field_max(STEREO_THRESHOLDS_UNIQUENESS_MASK, STEREO_THRESHOLDS_UNIQUENESS_LSB);
    const int tolerance_max =
        (int)field_max(STEREO_THRESHOLDS_LR_TOLERANCE_MASK, STEREO_THRESHOLDS_LR_TOLERANCE_LSB);
    const uint32_t min_disp = (uint32_t)config->min_disp;
    int status;
    int i;
    if (!within(config->width, 1, build->max_width) ||
        !within(config->height, 1, build->max_height) || !within(config->ndisp, 1, build->ndisp) ||
        !within(config->window, 1, build->window) || config->window % 2 == 0 ||
        !within(config->min_disp, -build->max_min_disp, build->max_min_disp) ||
        !within(config->uniqueness, 0, uniqueness_max) ||
        !within(config->lr_tolerance, 0, tolerance_max)) {
        return STEREO_E_RANGE;
    }
    status = check_kernel(build, config);
    if (status != STEREO_OK) {
        return status;
    }
    dev->write(dev->context, STEREO_REG_FRAME,
               (uint32_t)(STEREO_FIELD(STEREO_FRAME_WIDTH, config->width) |
                          STEREO_FIELD(STEREO_FRAME_HEIGHT, config->height)));
    dev->write(dev->context, STEREO_REG_MATCH,
               (uint32_t)(STEREO_FIELD(STEREO_MATCH_NDISP, config->ndisp) |
                          STEREO_FIELD(STEREO_MATCH_RADIUS, config->window / 2) |
                          STEREO_FIELD(STEREO_MATCH_USE_CA, config->use_ca != 0)));
    dev->write(dev->context, STEREO_REG_STAGE6,
               (uint32_t)(STEREO_FIELD(STEREO_STAGE6_MIN_DISP, min_disp) |
                          STEREO_FIELD(STEREO_STAGE6_UNIQUENESS_EN, config->uniqueness_en != 0) |
                          STEREO_FIELD(STEREO_STAGE6_LR_EN, config->lr_en != 0) |
                          STEREO_FIELD(STEREO_STAGE6_SUBPIXEL_EN, config->subpixel_en != 0)));
    dev->write(dev->context, STEREO_REG_THRESHOLDS,
               (uint32_t)(STEREO_FIELD(STEREO_THRESHOLDS_UNIQUENESS, config->uniqueness) |
                          STEREO_FIELD(STEREO_THRESHOLDS_LR_TOLERANCE, config->lr_tolerance)));
    if (config->kernel != 0) {
        /* The taps centred in the build's window, zeros outside. */
        const int offset = (build->window - config->window) / 2;
        for (i = 0; i < build->window; ++i) {
            const int tap = i - offset;
            const uint32_t value = (tap >= 0 && tap < config->window) ? config->kernel[tap] : 0u;
            dev->write(dev->context, STEREO_REG_KERNEL(i),
                       (uint32_t)STEREO_FIELD(STEREO_KERNEL_TAP, value));
        }
    }
    return STEREO_OK;
}

void stereo_soft_reset(const stereo_device* dev) {
    dev->write(dev->context, STEREO_REG_CONTROL,
               (uint32_t)STEREO_FIELD(STEREO_CONTROL_SOFT_RESET, 1));
}

void stereo_read_counters(const stereo_device* dev, stereo_counters* counters) {
    counters->status = dev->read(dev->context, STEREO_REG_STATUS);
    counters->frames_in = dev->read(dev->context, STEREO_REG_FRAMES_IN);
    counters->frames_out = dev->read(dev->context, STEREO_REG_FRAMES_OUT);
    counters->stalls = dev->read(dev->context, STEREO_REG_STALLS);
}

int stereo_wait_frames(const stereo_device* dev, uint32_t frames_out, uint32_t max_polls) {
    uint32_t poll;
    for (poll = 0; poll < max_polls; ++poll) {
        if (dev->read(dev->context, STEREO_REG_FRAMES_OUT) >= frames_out) {
            return dev->read(dev->context, STEREO_REG_STATUS) == 0 ? STEREO_OK : STEREO_E_STATUS;
        }
    }
    return STEREO_E_TIMEOUT;
}

const char* stereo_error_text(int code) {
    switch (code) {
        case STEREO_OK:
            return "ok";
        case STEREO_E_ID:
            return "no stereo core: the ID register does not read \"STER\"";
        case STEREO_E_VERSION:
            return "the core's register map has another major version";
        case STEREO_E_RANGE:
            return "a configuration value is outside what the core was built for";
        case STEREO_E_KERNEL:
            return "the kernel taps do not fit the core or the window";
        case STEREO_E_TIMEOUT:
            return "the frames did not arrive in time";
        case STEREO_E_STATUS:
            return "the core reports a status bit";
        default:
            return "unknown error";
    }
}
