/* gd_remainder (core/remainder_impl.h) against C's fmod, bit for bit: the laws wrap their
 * angles with it, and every transient number stays what fmod gave only if it is exact. */
#include <stdint.h>

#include "core/remainder_impl.h"
#include "harness.h"

static uint64_t next(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

static double uniform(uint64_t *s)
{
    return (double)(next(s) >> 11) / 9007199254740992.0;
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* random magnitudes 1e-10..1e30, exact multiples of the period (remainder 0, signed), their
 * neighbours one ulp below (remainder just under p: the quotient rounds up to the next
 * integer) and negative arguments; periods of a shaft turn, of tooth meshes, and odd ones */
TEST(remainder_equals_fmod_bit_for_bit)
{
    const double period[] = {6.283185307179586,
                             6.283185307179586 / 23,
                             6.283185307179586 / 67,
                             0.1,
                             1.0,
                             3.0,
                             1e-3,
                             7.3e-5};
    uint64_t s = 88172645463325252ull;
    long differ = 0, n = 0;
    for (int k = 0; k < 8; k++)
        for (int i = 0; i < 20000; i++) {
            const double p = period[k];
            double x = (uniform(&s) - 0.3) * pow(10.0, uniform(&s) * 40.0 - 10.0);
            if (i % 7 == 0) x = p * (double)(long)(uniform(&s) * 1e6);
            if (i % 11 == 0) x = nextafter(p * (double)(long)(uniform(&s) * 1e4), 0.0);
            if (i % 13 == 0) x = -x;
            differ += !same_bits(gd_remainder(x, p), fmod(x, p));
            n++;
        }
    CHECK(differ == 0);
    CHECK(same_bits(gd_remainder(-2.0 * period[0], period[0]), -0.0));
    CHECK(isnan(gd_remainder(NAN, 1.0)) && isnan(gd_remainder(INFINITY, 1.0)));
    CHECK(same_bits(gd_remainder(1e300, 0.1), fmod(1e300, 0.1))); /* beyond 2^52 periods */
    printf("  %ld of %ld arguments differ from fmod\n", differ, n);
}

RUN_TESTS(T(remainder_equals_fmod_bit_for_bit))
