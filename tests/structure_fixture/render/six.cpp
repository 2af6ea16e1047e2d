// A fixture for scripts/check_structure.py: a render function over the
// parameter limit, which the check must name.
namespace fixture {
int six(int a, int b, int c, int d, int e, int f) { return a + b + c + d + e + f; }
int five(int a, int b, int c, int d, int e) { return a + b + c + d + e; }
}  // namespace fixture
