// A fixture for scripts/check_structure.py: with --max-function 4, a
// function of six lines the check must name, and one of four it must not.
namespace fixture {
int six_lines(int a) {
  int b = a + 1;
  int c = b * 2;
  int d = c - a;
  return d;
}
int four_lines(int a) {
  int b = a + 1;
  return b;
}
}  // namespace fixture
