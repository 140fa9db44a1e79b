"""The mutation rules on hand-written snippets: what each rule produces, what it must leave alone
(comments, strings, preprocessor lines), stable ids and a seeded draw."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mutants import generate, mask  # noqa: E402
import mutate  # noqa: E402


def edits(src, rule_prefix=""):
    return sorted(m.apply(src) for m in generate("x.cpp", src) if m.rule.startswith(rule_prefix))


def test_mask_blanks_comments_strings_and_preprocessor_lines_keeping_offsets():
    src = '#include "a + b.h"\nint x = 1; // 2 + 3\nconst char* s = "4 < 5"; /* 6 * 7 */ char c = \'+\';\n'
    m = mask(src)
    assert len(m) == len(src)
    assert m.count("\n") == src.count("\n")
    for hidden in ("a + b", "2 + 3", "4 < 5", "6 * 7", "'+'"):
        assert hidden not in m
    assert "int x = 1;" in m


def test_nothing_fires_inside_comments_or_strings():
    src = '// if (a < b) return 1;\nconst char* s = "x + 2";\n'
    assert generate("x.cpp", src) == []


def test_relational_and_arithmetic_swaps():
    src = "bool f(int a, int b) { return a < b; }\n"
    out = edits(src, "op")
    assert "bool f(int a, int b) { return a <= b; }\n" in out
    assert "bool f(int a, int b) { return a > b; }\n" in out
    assert len(out) == 2
    src = "int g(int a, int b) { return a + b * 3; }\n"
    out = edits(src, "op")
    assert "int g(int a, int b) { return a - b * 3; }\n" in out
    assert "int g(int a, int b) { return a + b / 3; }\n" in out


def test_compound_assignment_becomes_plain_assignment():
    src = "void h(int& s, int v) { s += v; }\n"
    out = edits(src, "op")
    assert "void h(int& s, int v) { s = v; }\n" in out
    assert "void h(int& s, int v) { s -= v; }\n" in out


def test_dropped_terms_and_factors():
    src = "double k(double a, double b, double c) { return a + b * c - 1.0; }\n"
    out = edits(src, "drop")
    assert "double k(double a, double b, double c) { return a - 1.0; }\n" in out       # + b * c
    assert "double k(double a, double b, double c) { return a + b - 1.0; }\n" in out   # * c
    assert "double k(double a, double b, double c) { return a + b * c; }\n" in out     # - 1.0
    src = "double q(double a, double b) { return (a + b) * 0.5; }\n"
    assert "double q(double a, double b) { return (a + b); }\n" in edits(src, "drop")


def test_constants_zero_double_and_plus_minus_one():
    src = "int n() { return 8; }\n"
    assert edits(src, "const") == sorted(["int n() { return 0; }\n", "int n() { return 16; }\n",
                                          "int n() { return 9; }\n", "int n() { return 7; }\n"])
    src = "float t() { return 0.25f; }\n"
    assert "float t() { return 0.5f; }\n" in edits(src, "const")
    assert "float t() { return 0.0f; }\n" in edits(src, "const")
    src = "int z() { return 0; }\n"
    assert edits(src, "const") == ["int z() { return 1; }\n"]
    # identifiers with digits and literal suffix parts are not constants
    assert edits("int v2 = x3;\n", "const") == []


def test_swapped_arguments_clamp_min_max_and_early_exit():
    src = "float f(float x, float lo) { return std::clamp(x, lo, hi); }\n"
    assert "float f(float x, float lo) { return x; }\n" in edits(src, "drop clamp")
    assert "float f(float x, float lo) { return std::clamp(lo, x, hi); }\n" in edits(src, "swap")
    src = "int m(int a, int b) { return std::min(a, b + 1); }\n"
    out = edits(src, "drop min")
    assert out == sorted(["int m(int a, int b) { return a; }\n", "int m(int a, int b) { return b + 1; }\n"])
    # dot and distance commute exactly: no swap is made of them.
    assert edits("float d(vec3 a, vec3 b) { return glm::dot(a, b) + pow(a.x, b.x); }\n", "swap") == [
        "float d(vec3 a, vec3 b) { return glm::dot(a, b) + pow(b.x, a.x); }\n"]
    src = "int e(int n) {\n  if (n == 0) return -1;\n  return n;\n}\n"
    assert edits(src, "drop early") == ["int e(int n) {\n\n  return n;\n}\n"]


def test_ids_are_stable_across_unrelated_edits_and_distinct():
    a = "int f(int a, int b) {\n  return a < b;\n}\n"
    b = "// a comment that moves every line down\n\n" + a
    ida = {m.rule + m.replacement: m.id for m in generate("x.cpp", a)}
    idb = {m.rule + m.replacement: m.id for m in generate("x.cpp", b)}
    assert ida == idb
    ms = generate("x.cpp", "int f(int a) { return a + 1 + a + 1; }\n")
    assert len({m.id for m in ms}) == len(ms)


def test_the_draw_depends_on_the_seed_only():
    ms = generate("x.cpp", "int f(int a, int b) { return a * 3 + b * 5 - (a < b ? 7 : 9); }\n")
    one = [m.id for m in mutate.sample(ms, 5, 1)]
    assert one == [m.id for m in mutate.sample(ms, 5, 1)]
    assert one != [m.id for m in mutate.sample(ms, 5, 2)]
    assert len(set(one)) == 5


def test_test_runs_name_binaries_and_their_kernel_tables():
    assert mutate.parse_runs("test_raster") == [("test_raster", None)]
    assert mutate.parse_runs("test_raster,test_raster@scalar,test_raytrace@avx2") == [
        ("test_raster", None), ("test_raster", "scalar"), ("test_raytrace", "avx2")]
    for bad in ("test_raster@sse9", "@scalar", "test_raster,,test_raytrace"):
        assert mutate.parse_runs(bad) is None, bad


def test_an_edit_elsewhere_keeps_the_rest_of_the_draw():
    base = "int f(int a, int b) { return a * 3 + b * 5 - (a < b ? 7 : 9); }\n"
    more = base + "int g(int c) { return c + 11; }\n"
    one = {m.id for m in mutate.sample(generate("x.cpp", base), 6, 1)}
    two = {m.id for m in mutate.sample(generate("x.cpp", more), 6, 1)}
    # g's mutants may take places in the draw; every other place keeps its mutant.
    g_ids = {m.id for m in generate("x.cpp", more)} - {m.id for m in generate("x.cpp", base)}
    assert two - g_ids <= one
    assert len(one - two) == len(two & g_ids)
