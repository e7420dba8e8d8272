#include "geardyn/units.h"
#include "harness.h"

static double q(const char *s, gd_qty k)
{
    double v = NAN;
    gd_error why;
    if (gd_parse_quantity(s, k, &v, &why)) return NAN;
    return v;
}

TEST(plain_numbers_are_si)
{
    CHECK_REL(q("2.75e9", GD_QTY_STIFFNESS), 2.75e9, 1e-15);
    CHECK_REL(q("  0.5 ", GD_QTY_LENGTH), 0.5, 1e-15);
}

TEST(units_convert_to_si)
{
    CHECK_REL(q("3000 rpm", GD_QTY_ANGULAR_SPEED), 3000.0 * 2.0 * M_PI / 60.0, 1e-14);
    CHECK_REL(q("20 deg", GD_QTY_ANGLE), 20.0 * M_PI / 180.0, 1e-14);
    CHECK_REL(q("25.4 mm", GD_QTY_LENGTH), 0.0254, 1e-14);
    CHECK_REL(q("2.75e9 N/m", GD_QTY_STIFFNESS), 2.75e9, 1e-14);
    CHECK_REL(q("35 MN/m", GD_QTY_STIFFNESS), 35e6, 1e-14);
    CHECK_REL(q("9.483 kN*m/rad", GD_QTY_ROT_STIFFNESS), 9483.0, 1e-14);
    CHECK_REL(q("9.483 kN m/rad", GD_QTY_ROT_STIFFNESS), 9483.0, 1e-14);
    CHECK_REL(q("115 N*m", GD_QTY_ROT_STIFFNESS), 115.0, 1e-14); /* rad implicit */
    CHECK_REL(q("830 kg*mm^2", GD_QTY_INERTIA), 830e-6, 1e-14);
    CHECK_REL(q("7800 kg/m^3", GD_QTY_DENSITY), 7800.0, 1e-14);
    CHECK_REL(q("200 GPa", GD_QTY_PRESSURE), 2e11, 1e-14);
    CHECK_REL(q("200 N*s/m", GD_QTY_DAMPING), 200.0, 1e-14);
    CHECK_REL(q("10 Hz", GD_QTY_ANGULAR_SPEED), 20.0 * M_PI, 1e-14);
    CHECK_REL(q("6.895e-3 Pa*s", GD_QTY_VISCOSITY), 6.895e-3, 1e-14);
    CHECK_REL(q("12.7 um", GD_QTY_LENGTH), 12.7e-6, 1e-14);
    CHECK_REL(q("1 in", GD_QTY_LENGTH), 0.0254, 1e-14);
    CHECK_REL(q("3 g*mm", GD_QTY_MASS_LENGTH), 3e-6, 1e-14);
}

TEST(wrong_dimensions_and_garbage_are_rejected)
{
    double v;
    gd_error why;
    CHECK(gd_parse_quantity("20 mm", GD_QTY_ANGLE, &v, &why) != 0);
    CHECK(strstr(why.message, "rad") != NULL);
    CHECK(gd_parse_quantity("3 N/m", GD_QTY_DAMPING, &v, &why) != 0);
    CHECK(gd_parse_quantity("abc", GD_QTY_LENGTH, &v, &why) != 0);
    CHECK(gd_parse_quantity("3 furlongs", GD_QTY_LENGTH, &v, &why) != 0);
    CHECK(strstr(why.message, "furlongs") != NULL);
    CHECK(gd_parse_quantity("nan", GD_QTY_LENGTH, &v, &why) != 0);
    CHECK(gd_parse_quantity("inf mm", GD_QTY_LENGTH, &v, &why) != 0);
    CHECK(gd_parse_quantity("1 N/m/s", GD_QTY_DAMPING, &v, &why) != 0);
    CHECK(gd_parse_quantity("1 m^9", GD_QTY_LENGTH, &v, &why) != 0);
}

RUN_TESTS(T(plain_numbers_are_si), T(units_convert_to_si),
          T(wrong_dimensions_and_garbage_are_rejected))
