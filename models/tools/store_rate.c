/* How many 8-byte stores a cycle this core retires, for reading the generated code's
 * timings: a large output (g1's 35 x 35 mass matrix, 1,225 entries) and the values a long
 * kernel spills are all stores, and on some hosts stores, not arithmetic, bound the time.
 *
 *   gcc -O2 models/tools/store_rate.c -o /tmp/store_rate && /tmp/store_rate
 *
 * Prints the clock (from a chain of dependent additions, one a cycle) and the rate of
 * scalar stores to eight different cache lines and to one line, in loops of eight stores
 * (the loop's own work is one increment and one branch). x86-64 with AVX only (inline
 * assembly). */
#include <stdio.h>
#include <time.h>

static double buffer[1300] __attribute__((aligned(64)));

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e9 + t.tv_nsec;
}

/* Times n stores of eight `vmovsd` to the byte offsets o0..o7 of `buffer` a loop, and
 * prints ns a store and stores a cycle at `ghz`. */
#define TIME_STORES(label, o0, o1, o2, o3, o4, o5, o6, o7)                                  \
    do {                                                                                    \
        double start = now_ns();                                                            \
        for (long i = 0; i < n / 8; i++) {                                                  \
            double v = (double)i;                                                           \
            __asm__ volatile("vmovsd %0, " o0 "(%1)\n\tvmovsd %0, " o1 "(%1)\n\t"          \
                             "vmovsd %0, " o2 "(%1)\n\tvmovsd %0, " o3 "(%1)\n\t"          \
                             "vmovsd %0, " o4 "(%1)\n\tvmovsd %0, " o5 "(%1)\n\t"          \
                             "vmovsd %0, " o6 "(%1)\n\tvmovsd %0, " o7 "(%1)\n\t"          \
                             : : "x"(v), "r"(buffer) : "memory");                           \
        }                                                                                   \
        double ns = (now_ns() - start) / n;                                                 \
        printf("%s: %.3f ns each, %.2f a cycle\n", label, ns, 1.0 / (ns * ghz));            \
    } while (0)

int main(void) {
    const long n = 200000000;
    long x = 0;
    double t = now_ns();
    for (long i = 0; i < n / 4; i++)
        __asm__ volatile("add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0" : "+r"(x));
    double ghz = n / (now_ns() - t);
    printf("clock: %.2f GHz (dependent additions)\n", ghz);

    /* rows of a 35-column matrix of doubles, 280 bytes apart: eight different lines */
    TIME_STORES("stores to eight lines", "0", "280", "560", "840", "1120", "1400", "1680", "1960");
    TIME_STORES("stores to one line", "0", "8", "16", "24", "32", "40", "48", "56");
    return x == 0;
}
