// Implicit functions typed as text (muparser): values, dimensions and aliases, the same numbers as
// the compiled catalogue (and so the same trace), one clear error per kind of bad text, and
// separate objects evaluated on separate threads at once.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "../tracing/expect_identical.h"
#include "coxmesh/oracle/expression_function.h"
#include "coxmesh/oracle/implicit_oracle.h"
#include "coxmesh/tracing/trace_manifold.h"

using namespace coxmesh;

TEST(Expression, ValuesDimensionsAndAliases) {
  const FunctionPtr f = expression_function("x^2+y^2+z^2-1");
  EXPECT_EQ(f->ambient_dimension(), 3);
  EXPECT_EQ(f->codimension(), 1);
  double x[4] = {1, 2, 3, 4}, v[2];
  f->evaluate(x, v);
  EXPECT_EQ(v[0], 13.0);
  const FunctionPtr g = expression_function("x1^2+x2^2-1; x3 - x4", 4);
  EXPECT_EQ(g->codimension(), 2);
  g->evaluate(x, v);
  EXPECT_EQ(v[0], 4.0);
  EXPECT_EQ(v[1], -1.0);
  const FunctionPtr h = expression_function("x^2 + w = 2*pi");  // lhs = rhs, w = x4
  EXPECT_EQ(h->ambient_dimension(), 4);
  h->evaluate(x, v);
  EXPECT_DOUBLE_EQ(v[0], 5.0 - 2 * M_PI);
  EXPECT_EQ(expression_function("z")->ambient_dimension(), 3);
  EXPECT_EQ(expression_function("x1", 5)->ambient_dimension(), 5);
  EXPECT_EQ(expression_domain("x^2+y^2-4", 3)->codimension(), 1);
  EXPECT_EQ(expression_function("x < 0 ? -x : x - 1; y", 3)->codimension(), 2);
}

TEST(Expression, MatchesTheCompiledSphereExactly) {
  const FunctionPtr e = expression_function("x^2+y^2+z^2-1"), s = sphere(2, 3, 1.0);
  double x[3] = {0.3, -0.7, 0.11}, a, b;
  for (int i = 0; i < 100; ++i) {
    x[i % 3] += 0.0137 * i;
    e->evaluate(x, &a);
    s->evaluate(x, &b);
    EXPECT_EQ(a, b);
  }
  // And so the traces agree, bit for bit (and with them every cell complex built from them).
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.3);
  ImplicitOracle o1(t, e), o2(t, s);
  const TraceResult r1 = trace_manifold(t, o1, {{1, 0, 0}});
  const TraceResult r2 = trace_manifold(t, o2, {{1, 0, 0}});
  EXPECT_GT(r1.simplices.size(), 100u);
  expect_identical(r1, r2, "expression vs sphere");
}

TEST(Expression, SeparateObjectsOnSeparateThreads) {
  // An object is not thread-safe (its parsers share one array of variables), so the tracer asks
  // for one per worker; separate objects share nothing and give the one thread's values.
  constexpr int kThreads = 4, kPoints = 2000;
  const std::string text = "sin(x)*y - z^2; x + y*z";
  std::vector<std::vector<double>> values(kThreads, std::vector<double>(2 * kPoints));
  std::vector<std::thread> threads;
  for (int w = 0; w < kThreads; ++w)
    threads.emplace_back([&, w] {
      const FunctionPtr f = expression_function(text, 3);
      for (int i = 0; i < kPoints; ++i) {
        const double x[3] = {0.001 * i, 1.0 - 0.002 * i, 0.5 + 0.0003 * i};
        f->evaluate(x, values[w].data() + 2 * i);
      }
    });
  for (auto& t : threads) t.join();
  for (int i = 0; i < kPoints; ++i) {
    const double x = 0.001 * i, y = 1.0 - 0.002 * i, z = 0.5 + 0.0003 * i;
    ASSERT_DOUBLE_EQ(values[0][2 * i], std::sin(x) * y - z * z) << i;
    ASSERT_DOUBLE_EQ(values[0][2 * i + 1], x + y * z) << i;
  }
  for (int w = 1; w < kThreads; ++w) EXPECT_EQ(values[w], values[0]) << "thread " << w;
}

namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Expression, Errors) {
  auto has = [](const std::string& msg, const std::string& part) {
    return msg.find(part) != std::string::npos
               ? ::testing::AssertionSuccess()
               : ::testing::AssertionFailure() << "'" << msg << "' lacks '" << part << "'";
  };
  std::string e = error_of([] { expression_function("x^2+*y"); });
  EXPECT_TRUE(has(e, "position 5"));
  EXPECT_TRUE(has(e, "x^2+*y"));
  e = error_of([] { expression_function("x^2+y^2-1; (z"); });
  EXPECT_TRUE(has(e, "position 14"));  // the end of the second equation, in the whole text
  EXPECT_TRUE(has(error_of([] { expression_function("x^2+foo"); }), "unknown variable 'foo' at position 5"));
  EXPECT_TRUE(has(error_of([] { expression_function("x0+y"); }), "unknown variable 'x0'"));
  EXPECT_TRUE(has(error_of([] { expression_function("x3+x1", 2); }), "beyond the dimension d = 2"));
  EXPECT_TRUE(has(error_of([] { expression_function("x+x5"); }), "only for d <= 4"));
  EXPECT_TRUE(has(error_of([] { expression_function("x^2+y^2-1; x-y"); }), "fewer equations than the dimension"));
  EXPECT_TRUE(has(error_of([] { expression_function("x"); }), "give --dim"));
  EXPECT_TRUE(has(error_of([] { expression_function("x, y"); }), "separate equations with ';'"));
  EXPECT_TRUE(has(error_of([] { expression_function("x+y;;z"); }), "empty equation"));
  EXPECT_TRUE(has(error_of([] { expression_function("x=y=z"); }), "second '='"));
  EXPECT_TRUE(has(error_of([] { expression_function("x", 40); }), "not supported"));
  EXPECT_TRUE(has(error_of([] { expression_domain("x; y", 3); }), "2 expressions"));
  EXPECT_TRUE(has(error_of([] { expression_domain("x4", 3); }), "beyond the dimension d = 3"));
}
