/* stereo_driver: a small C99 driver for stereo_axil_top (docs/integration.md, README.md here).
 *
 * The driver reaches the registers through two functions of the caller's (a memory-mapped
 * pointer on a processor, a simulator's bus model in a testbench), so it runs anywhere:
 *
 *   static uint32_t mmio_read(void *base, uint32_t offset)
 *   { return *(volatile uint32_t *)((char *)base + offset); }
 *   static void mmio_write(void *base, uint32_t offset, uint32_t value)
 *   { *(volatile uint32_t *)((char *)base + offset) = value; }
 *   stereo_device dev = {mmio_read, mmio_write, (void *)0x44A00000};
 *
 * Every function returns STEREO_OK (0) or a negative STEREO_E_* code; stereo_error_text names
 * it. Nothing is written when a check fails. The register map is drivers/c/stereo_regs.h,
 * generated from the same definition as the RTL's. */
#ifndef STEREO_DRIVER_H
#define STEREO_DRIVER_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct stereo_device {
    uint32_t (*read)(void* context, uint32_t offset);
    void (*write)(void* context, uint32_t offset, uint32_t value);
    void* context;
} stereo_device;

/* What the core was built for: the read-only registers MAX_SIZE and BUILD, and VERSION. */
typedef struct stereo_build {
    uint32_t version;
    int max_width;
    int max_height;
    int ndisp;  /* NDISP: the most labels a frame may search */
    int window; /* WINDOW: the largest window */
    int max_min_disp;
    int runtime_kernel; /* 1: the KERNEL registers are used */
    int cost;           /* STEREO_COST_* */
} stereo_build;

/* One frame configuration (the model's MatchParams with stage 6). */
typedef struct stereo_config {
    int width;
    int height;
    int ndisp;  /* labels searched: d = min_disp .. min_disp + ndisp - 1 */
    int window; /* odd, at most the build's window */
    int use_ca;
    int min_disp;
    int uniqueness_en;
    int uniqueness; /* ratio U, percent */
    int lr_en;
    int lr_tolerance; /* labels */
    int subpixel_en;
    /* `window` taps summing to 256 (the model's gaussian_kernel, e.g. from `stereo vectors`'
     * config.hex), written centred into the KERNEL registers; NULL leaves the KERNEL registers as
     * they are (after a reset: the default kernel of the build's window). A core built with
     * RUNTIME_KERNEL = 0 takes only NULL and its own window. */
    const uint16_t* kernel;
} stereo_config;

typedef struct stereo_counters {
    uint32_t status; /* STATUS: sticky, STEREO_STATUS_*_MASK bits */
    uint32_t frames_in;
    uint32_t frames_out;
    uint32_t stalls;
} stereo_counters;

enum {
    STEREO_OK = 0,
    STEREO_E_ID = -1,      /* the ID register does not read STEREO_REGMAP_ID */
    STEREO_E_VERSION = -2, /* another major version of the register map */
    STEREO_E_RANGE = -3,   /* a configuration value the build cannot take */
    STEREO_E_KERNEL = -4,  /* kernel taps not possible for this build or window */
    STEREO_E_TIMEOUT = -5, /* the frames did not arrive within the polls */
    STEREO_E_STATUS = -6   /* STATUS has a bit set */
};

/* Reads ID, VERSION, MAX_SIZE and BUILD into *build. */
int stereo_probe(const stereo_device* dev, stereo_build* build);
/* Checks *config against *build, then writes FRAME, MATCH, STAGE6, THRESHOLDS and the kernel.
 * Takes effect from the next frame the core starts. */
int stereo_configure(const stereo_device* dev, const stereo_build* build,
                     const stereo_config* config);
/* CONTROL.soft_reset: clears the core's state, STATUS and the counters (not the configuration). */
void stereo_soft_reset(const stereo_device* dev);
void stereo_read_counters(const stereo_device* dev, stereo_counters* counters);
/* Polls until FRAMES_OUT reaches `frames_out` (at most `max_polls` reads of it); STEREO_E_STATUS
 * when STATUS is not 0 then. */
int stereo_wait_frames(const stereo_device* dev, uint32_t frames_out, uint32_t max_polls);
const char* stereo_error_text(int code);

#ifdef __cplusplus
}
#endif

#endif /* STEREO_DRIVER_H */
