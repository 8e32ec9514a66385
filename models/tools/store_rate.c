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

int main(void) {
    const long n = 200000000;
    long x = 0;
    double t = now_ns();
    for (long i = 0; i < n / 4; i++)
        __asm__ volatile("add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0" : "+r"(x));
    double ghz = n / (now_ns() - t);
    printf("clock: %.2f GHz (dependent additions)\n", ghz);

    t = now_ns();
    for (long i = 0; i < n / 8; i++) {
        double v = (double)i;
        /* rows of a 35-column matrix of doubles: 280 bytes apart, eight different lines */
        __asm__ volatile("vmovsd %0, 0(%1)\n\tvmovsd %0, 280(%1)\n\tvmovsd %0, 560(%1)\n\t"
                         "vmovsd %0, 840(%1)\n\tvmovsd %0, 1120(%1)\n\tvmovsd %0, 1400(%1)\n\t"
                         "vmovsd %0, 1680(%1)\n\tvmovsd %0, 1960(%1)\n\t"
                         : : "x"(v), "r"(buffer) : "memory");
    }
    double ns = (now_ns() - t) / n;
    printf("stores to eight lines: %.3f ns each, %.2f a cycle\n", ns, 1.0 / (ns * ghz));

    t = now_ns();
    for (long i = 0; i < n / 8; i++) {
        double v = (double)i;
        __asm__ volatile("vmovsd %0, 0(%1)\n\tvmovsd %0, 8(%1)\n\tvmovsd %0, 16(%1)\n\t"
                         "vmovsd %0, 24(%1)\n\tvmovsd %0, 32(%1)\n\tvmovsd %0, 40(%1)\n\t"
                         "vmovsd %0, 48(%1)\n\tvmovsd %0, 56(%1)\n\t"
                         : : "x"(v), "r"(buffer) : "memory");
    }
    ns = (now_ns() - t) / n;
    printf("stores to one line: %.3f ns each, %.2f a cycle\n", ns, 1.0 / (ns * ghz));
    return x == 0;
}
