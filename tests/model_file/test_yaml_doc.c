#include "harness.h"
#include "model_file/yaml_doc_impl.h"

TEST(tree_keeps_lines)
{
    gd_error err;
    gd_ydoc *doc;
    REQUIRE(gd_ydoc_load_string("a: 1\nb:\n  - x: 2 mm\n  - [1, 2]\n", "t.yaml", &doc, &err) ==
            GD_OK);
    REQUIRE(doc->root && doc->root->kind == GD_Y_MAP);
    const gd_ynode *b = gd_ymap_get(doc->root, "b");
    REQUIRE(b && b->kind == GD_Y_SEQ && b->n == 2);
    CHECK(b->items[0]->line == 3);
    gd_yreader r = {"t.yaml", &err};
    double x = 0;
    CHECK(gd_yread_qty(&r, b->items[0], "x", "b[0]", GD_QTY_LENGTH, GD_YREQ, &x, NULL) == GD_OK);
    CHECK_REL(x, 0.002, 1e-14);
    gd_ydoc_free(doc);
}

TEST(syntax_errors_are_located)
{
    gd_error err;
    gd_ydoc *doc;
    CHECK(gd_ydoc_load_string("a: [1, 2\nb: 3\n", "bad.yaml", &doc, &err) == GD_EINPUT);
    CHECK(doc == NULL);
    CHECK(err.line >= 1);
    CHECK_STR(err.file, "bad.yaml");
    CHECK(strstr(err.message, "syntax") != NULL);
}

TEST(duplicate_keys_rejected)
{
    gd_error err;
    gd_ydoc *doc;
    CHECK(gd_ydoc_load_string("a: 1\na: 2\n", "d.yaml", &doc, &err) == GD_EINPUT);
    CHECK(err.line == 2);
    CHECK(strstr(err.message, "duplicate") != NULL);
}

TEST(unknown_key_suggests_nearest)
{
    gd_error err;
    gd_ydoc *doc;
    REQUIRE(gd_ydoc_load_string("lenght: 1\n", "k.yaml", &doc, &err) == GD_OK);
    gd_yreader r = {"k.yaml", &err};
    static const char *const keys[] = {"length", "material", NULL};
    CHECK(gd_ycheck_keys(&r, doc->root, "shafts[0]", keys) == GD_EINPUT);
    CHECK(strstr(err.hint, "length") != NULL);
    CHECK_STR(err.field, "shafts[0].lenght");
    gd_ydoc_free(doc);
}

TEST(typed_readers_check_values)
{
    gd_error err;
    gd_ydoc *doc;
    REQUIRE(gd_ydoc_load_string("m: -2\nn: 3.5\nc: blue\nb: yes\nq: [1]\n", "v.yaml", &doc, &err) ==
            GD_OK);
    gd_yreader r = {"v.yaml", &err};
    double m;
    CHECK(gd_yread_qty(&r, doc->root, "m", "", GD_QTY_MASS, GD_YPOS, &m, NULL) == GD_EINPUT);
    CHECK(err.line == 1);
    long n;
    CHECK(gd_yread_int(&r, doc->root, "n", "", 0, 10, 0, &n, NULL) == GD_EINPUT);
    static const char *const colours[] = {"red", "green", NULL};
    int idx;
    CHECK(gd_yread_str(&r, doc->root, "c", "", colours, 0, NULL, &idx, NULL) == GD_EINPUT);
    CHECK(strstr(err.hint, "red") != NULL);
    int b = 0;
    CHECK(gd_yread_bool(&r, doc->root, "b", "", 0, &b, NULL) == GD_OK && b == 1);
    CHECK(gd_yread_qty(&r, doc->root, "q", "", GD_QTY_MASS, 0, &m, NULL) == GD_EINPUT);
    CHECK(gd_yread_qty(&r, doc->root, "zz", "", GD_QTY_MASS, GD_YREQ, &m, NULL) == GD_EINPUT);
    CHECK(strstr(err.message, "missing") != NULL);
    gd_ydoc_free(doc);
}

RUN_TESTS(T(tree_keeps_lines), T(syntax_errors_are_located), T(duplicate_keys_rejected),
          T(unknown_key_suggests_nearest), T(typed_readers_check_values))
