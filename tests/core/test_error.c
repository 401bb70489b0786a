/* test_error — the error record's block base (rd_error.h): paths relative to
 * the block entered, '@' in a message for the base (a '%' in the base kept
 * literal), enter/leave nesting, first error wins, rd_error_forward copying
 * as it stands, and the ring's validator under a lift's /ring and a pack's
 * /rings/1/ring giving the same words at both places. */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "rd_error.h"
#include "rd_ring.h"

static void test_base(void)
{
    rd_error e;
    rd_error_init(&e);
    CHECK(e.base[0] == '\0', "init clears the base");
    size_t m = rd_error_enter(&e, "/rings/1");
    CHECK(m == 0 && strcmp(e.base, "/rings/1") == 0, "enter appends (%s)", e.base);
    size_t m2 = rd_error_enter(&e, "/ring");
    CHECK(m2 == 8 && strcmp(e.base, "/rings/1/ring") == 0, "nested (%s)", e.base);
    rd_error_leave(&e, m2);
    CHECK(strcmp(e.base, "/rings/1") == 0, "leave truncates to the mark (%s)", e.base);
    rd_error_enter(&e, "/ring");
    rd_error_set(&e, RD_EINVAL, "/diameter", "@/diameter = %g m; @ twice.", 2.5);
    CHECK(strcmp(e.path, "/rings/1/ring/diameter") == 0, "path is base + path (%s)", e.path);
    CHECK(strcmp(e.message, "/rings/1/ring/diameter = 2.5 m; /rings/1/ring twice.") == 0,
          "each @ is the base (%s)", e.message);
    rd_error_set(&e, RD_ELIMIT, "/other", "second");
    CHECK(e.code == RD_EINVAL && strcmp(e.path, "/rings/1/ring/diameter") == 0,
          "the first error wins");
    rd_error_leave(&e, m);
    CHECK(e.base[0] == '\0', "back at the root");

    rd_error_init(&e);
    rd_error_enter(&e, "/a%d%s");
    rd_error_set(&e, RD_EINVAL, "/b", "@/b = %d.", 7);
    CHECK(strcmp(e.message, "/a%d%s/b = 7.") == 0, "a '%%' in the base is kept (%s)", e.message);
    CHECK(strcmp(e.path, "/a%d%s/b") == 0, "and in the path (%s)", e.path);

    rd_error_init(&e);
    rd_error_set(&e, RD_EINVAL, "/x", "@/x at the root, 100%% sure");
    CHECK(strcmp(e.path, "/x") == 0 && strcmp(e.message, "/x at the root, 100% sure") == 0,
          "no base: @ is empty (%s)", e.message);

    rd_error_init(&e);
    rd_error_enter(&e, "/numerics");
    CHECK(rd_error_range(2.0, 0.0, 1.0, "/rtol", "", &e) == RD_EINVAL &&
              strcmp(e.path, "/numerics/rtol") == 0 &&
              strcmp(e.message, "/numerics/rtol = 2 is out of range: allowed 0 to 1.") == 0,
          "range: base + path in path and message (%s)", e.message);
    rd_error_init(&e);
    CHECK(rd_error_range_in("/output", -1.0, 0.0, 1.0, "/step_deg", "deg", &e) == RD_EINVAL &&
              strcmp(e.path, "/output/step_deg") == 0 && e.base[0] == '\0',
          "range_in enters and leaves (%s, base '%s')", e.path, e.base);

    CHECK(rd_error_enter(NULL, "/x") == 0, "NULL err: enter is a no-op");
    rd_error_leave(NULL, 0);
    CHECK(rd_error_set(NULL, RD_EINVAL, "/x", "@") == RD_EINVAL, "NULL err: set returns the code");
}

static void test_forward(void)
{
    rd_error local, e;
    rd_error_init(&local);
    rd_error_init(&e);
    rd_error_enter(&e, "/engine");
    rd_error_enter(&local, "/bore");
    rd_error_set(&local, RD_EINVAL, "/diameter", "@/diameter is wrong.");
    CHECK(rd_error_forward(&e, &local) == RD_EINVAL && strcmp(e.path, "/bore/diameter") == 0 &&
              strcmp(e.message, "/bore/diameter is wrong.") == 0 && strcmp(e.base, "/engine") == 0,
          "forward copies as it stands, the base applied once (%s)", e.path);
    rd_error other;
    rd_error_init(&other);
    rd_error_set(&other, RD_ENOMEM, "", "later");
    rd_error_forward(&e, &other);
    CHECK(e.code == RD_EINVAL, "forward: the first error wins");
    rd_error_init(&other);
    rd_error_init(&e);
    CHECK(rd_error_forward(&e, &other) == RD_OK && e.code == RD_OK, "forwarding no error");
}

/* The same ring validator at a lift's /ring and a pack's /rings/1/ring. */
static void test_ring_blocks(void)
{
    rd_ring_params p;
    rd_ring_params_default(&p);
    p.axial_height = 1e-4; /* b / h = 29 */
    const char *at[2] = {"/ring", "/rings/1/ring"};
    for (int k = 0; k < 2; k++) {
        rd_error e;
        rd_error_init(&e);
        if (k == 1)
            rd_error_enter(&e, "/rings/1");
        size_t m = rd_error_enter(&e, "/ring");
        CHECK(rd_ring_validate(&p, 0, &e) == RD_EINVAL, "refused");
        rd_error_leave(&e, m);
        char path[64], words[64];
        snprintf(path, sizeof path, "%s/axial_height", at[k]);
        snprintf(words, sizeof words, "%s/axial_height = 0.0001 m gives", at[k]);
        CHECK(strcmp(e.path, path) == 0 && strncmp(e.message, words, strlen(words)) == 0,
              "%s: %s: %s", at[k], e.path, e.message);
    }
    rd_error e;
    rd_error_init(&e);
    CHECK(rd_ring_scene_validate(&p, 20, 0, &e) == RD_EINVAL &&
              strcmp(e.path, "/ring/axial_height") == 0 && e.base[0] == '\0',
          "the scene's validator enters /ring and leaves it (%s)", e.path);
    rd_ring_params_default(&p);
    rd_error_init(&e);
    CHECK(rd_ring_scene_validate(&p, 2, 0, &e) == RD_EINVAL &&
              strcmp(e.path, "/discretization/segments") == 0 &&
              strncmp(e.message, "/discretization/segments = 2", 28) == 0,
          "segments under /discretization (%s)", e.message);
}

int main(void)
{
    test_base();
    test_forward();
    test_ring_blocks();
    return check_done();
}
