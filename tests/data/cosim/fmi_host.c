/* A minimal FMI 2.0 co-simulation host in C (no Python of its own), for tests/test_cosim_fmu.py.
 *
 * Loads an FMU's unpacked binary with dlopen, rolls the wheel at a fixed height along x for
 * n steps of dt and prints the largest FZ. Arguments:
 *   binary resources-uri guid vr_X_WC vr_Z_WC vr_VX_WC vr_ROTSPEED vr_INITIAL_LOAD vr_FZ
 *   z speed load steps dt
 */
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

typedef void *component;
typedef struct {
    void (*logger)(void *, const char *, int, const char *, const char *, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, int);
    void *componentEnvironment;
} callbacks;

static void logger(void *env, const char *name, int status, const char *category, const char *message, ...)
{
    va_list args;
    va_start(args, message);
    printf("[%s status %d] ", name, status);
    vprintf(message, args);
    printf("\n");
    va_end(args);
}

int main(int argc, char **argv)
{
    if (argc != 15) {
        printf("usage: %s binary resources guid vrX vrZ vrVX vrROT vrLOAD vrFZ z speed load steps dt\n", argv[0]);
        return 2;
    }
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        printf("dlopen failed: %s\n", dlerror());
        return 1;
    }
    component (*instantiate)(const char *, int, const char *, const char *, const callbacks *, int, int) =
        dlsym(lib, "fmi2Instantiate");
    int (*setup)(component, int, double, double, int, double) = dlsym(lib, "fmi2SetupExperiment");
    int (*enter)(component) = dlsym(lib, "fmi2EnterInitializationMode");
    int (*leave)(component) = dlsym(lib, "fmi2ExitInitializationMode");
    int (*set_real)(component, const unsigned *, size_t, const double *) = dlsym(lib, "fmi2SetReal");
    int (*get_real)(component, const unsigned *, size_t, double *) = dlsym(lib, "fmi2GetReal");
    int (*do_step)(component, double, double, int) = dlsym(lib, "fmi2DoStep");
    int (*terminate)(component) = dlsym(lib, "fmi2Terminate");
    void (*free_instance)(component) = dlsym(lib, "fmi2FreeInstance");

    unsigned inputs[4] = {atoi(argv[4]), atoi(argv[5]), atoi(argv[6]), atoi(argv[7])};
    unsigned load_vr = atoi(argv[8]), fz_vr = atoi(argv[9]);
    double z = atof(argv[10]), v = atof(argv[11]), load = atof(argv[12]), dt = atof(argv[14]);
    int steps = atoi(argv[13]);

    callbacks cb = {logger, calloc, free, NULL, NULL};
    component c = instantiate("wheel", 1, argv[3], argv[2], &cb, 0, 1);
    if (!c) {
        printf("fmi2Instantiate failed\n");
        return 1;
    }
    double start[4] = {0.0, z, v, v / z};
    if (setup(c, 0, 0.0, 0.0, 0, 0.0) || enter(c) || set_real(c, &load_vr, 1, &load) ||
        set_real(c, inputs, 4, start) || leave(c)) {
        printf("initialisation failed\n");
        return 1;
    }
    double peak = 0.0, fz = 0.0;
    for (int k = 0; k < steps; k++) {
        double t = k * dt, now[4] = {v * t, z, v, v / z};
        if (set_real(c, inputs, 4, now) || do_step(c, t, dt, 1) || get_real(c, &fz_vr, 1, &fz)) {
            printf("step %d failed\n", k);
            return 1;
        }
        if (fz > peak)
            peak = fz;
    }
    printf("peak FZ %.6f N\n", peak);
    terminate(c);
    free_instance(c);
    return 0;
}
