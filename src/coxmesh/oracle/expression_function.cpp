// Implicit functions and domains from muparser expressions; see expression_function.h.
#include "coxmesh/oracle/expression_function.h"

#include <muParser.h>

#include <cctype>
#include <cmath>
#include <deque>
#include <numbers>
#include <vector>

#include "coxmesh/lattice/simplex.h"

namespace coxmesh {

namespace {

// One equation of the text: its expression for muparser and where it sits in the original text.
struct Equation {
  std::string expr;          // as given to muparser (lhs = rhs becomes (lhs)-(rhs))
  std::size_t start = 0;     // offset of the equation in the full text
  std::size_t lhs_size = 0;  // size of lhs when rewritten, else npos
};

std::string trim(std::string_view s, std::size_t& start) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  start += a;
  return std::string(s.substr(a, b - a));
}

// "… at position p of "text" (marked: abc >>> def)": p is 0-based in `text`, shown 1-based.
std::string where(std::string_view text, std::size_t p) {
  p = std::min(p, text.size());
  return "at position " + std::to_string(p + 1) + " of \"" + std::string(text) +
         "\" (marked: " + std::string(text.substr(0, p)) + " >>> " + std::string(text.substr(p)) + ")";
}

constexpr std::size_t kMaxExpressionLength = 1 << 16;

std::vector<Equation> split_equations(std::string_view text) {
  if (text.size() > kMaxExpressionLength)
    throw InputError("the expression is too long (" + std::to_string(text.size()) + " characters; at most " +
                     std::to_string(kMaxExpressionLength) + ")");
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos)
    throw InputError("the expression is empty: write the equations e1; e2; ... = 0 in x1..xd");
  std::vector<Equation> out;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = std::min(text.find(';', begin), text.size());
    Equation e;
    e.start = begin;
    e.expr = trim(text.substr(begin, end - begin), e.start);
    e.lhs_size = std::string::npos;
    if (e.expr.empty())
      throw InputError("empty equation " + where(text, e.start) +
                       ": write e1; e2; ... with one expression per equation");
    // A single '=' that is not part of a comparison (==, <=, >=, !=) is an equation lhs = rhs.
    std::size_t eq = std::string::npos;
    for (std::size_t i = 0; i < e.expr.size(); ++i) {
      if (e.expr[i] != '=') continue;
      const bool comparison = (i > 0 && std::string_view("<>!=").find(e.expr[i - 1]) != std::string_view::npos) ||
                              (i + 1 < e.expr.size() && e.expr[i + 1] == '=');
      if (comparison) continue;
      if (eq != std::string::npos) throw InputError("a second '=' " + where(text, e.start + i));
      eq = i;
    }
    if (eq != std::string::npos) {
      e.lhs_size = eq;
      std::string rewritten;  // appended piece by piece (GCC 12 warns falsely on chained + here)
      rewritten.append("(").append(e.expr, 0, eq).append(")-(").append(e.expr, eq + 1).append(")");
      e.expr = std::move(rewritten);
    }
    out.push_back(std::move(e));
    if (end == text.size()) break;
    begin = end + 1;
  }
  return out;
}

// Position in the full text of position p of the muparser expression of equation e.
std::size_t text_position(const Equation& e, std::size_t p) {
  if (e.lhs_size == std::string::npos) return e.start + p;
  if (p <= e.lhs_size + 1) return e.start + (p == 0 ? 0 : p - 1);  // "(" + lhs
  return e.start + (p >= e.lhs_size + 3 ? p - 3 : e.lhs_size);     // ")-(" + rhs
}

// Index 1..kMaxDimension of a variable name, 0 if it is not a variable of coxmesh.
int variable_index(const std::string& name, bool& alias) {
  alias = name.size() == 1;
  if (name == "x") return 1;
  if (name == "y") return 2;
  if (name == "z") return 3;
  if (name == "w") return 4;
  alias = false;
  if (name.size() < 2 || name[0] != 'x' || name[1] == '0' || name.size() > 4) return 0;
  int i = 0;
  for (std::size_t c = 1; c < name.size(); ++c) {
    if (!std::isdigit(static_cast<unsigned char>(name[c]))) return 0;
    i = 10 * i + (name[c] - '0');
  }
  return i;
}

// Position of the identifier `name` as a whole word in `s`, or 0.
std::size_t find_word(const std::string& s, const std::string& name) {
  auto is_name = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t p = s.find(name); p != std::string::npos; p = s.find(name, p + 1))
    if ((p == 0 || !is_name(s[p - 1])) && (p + name.size() >= s.size() || !is_name(s[p + name.size()]))) return p;
  return 0;
}

double* collect_variable(const char* /*name*/, void* storage) {
  auto* slots = static_cast<std::deque<double>*>(storage);
  slots->push_back(0.0);
  return &slots->back();
}

void define_constants(mu::Parser& p) { p.DefineConst("pi", std::numbers::pi); }

[[noreturn]] void parse_failure(std::string_view text, const Equation& e, const mu::Parser::exception_type& ex) {
  std::string msg = ex.GetMsg();
  if (const std::size_t at = msg.find(" at position "); at != std::string::npos) msg.erase(at);
  throw InputError("cannot parse the expression " +
                   where(text, text_position(e, static_cast<std::size_t>(std::max(ex.GetPos(), 0)))) + ": " + msg);
}

}  // namespace

struct ExpressionFunction::Impl {
  std::string text;
  int d = 0, k = 0;
  std::vector<double> variables;                     // x1..xd, bound to every parser
  std::vector<std::unique_ptr<mu::Parser>> parsers;  // one per equation (stable addresses)
};

ExpressionFunction::ExpressionFunction(std::string_view text, std::optional<int> dim, std::optional<int> max_equations)
    : impl_(std::make_unique<Impl>()) {
  impl_->text = std::string(text);
  const std::vector<Equation> equations = split_equations(text);

  // Pass 1: parse with a variable factory to learn which names are used and the dimension.
  int highest = 0;
  struct Use {
    std::string name;
    std::size_t position;
    bool alias;
  };
  std::vector<Use> uses;
  for (const Equation& e : equations) {
    std::deque<double> slots;
    mu::Parser p;
    define_constants(p);
    p.SetVarFactory(collect_variable, &slots);
    try {
      p.SetExpr(e.expr);
      for (const auto& [name, ptr] : p.GetUsedVar()) {
        bool alias = false;
        const int i = variable_index(name, alias);
        const std::size_t pos = text_position(e, find_word(e.expr, name));
        if (i == 0)
          throw InputError("unknown variable '" + name + "' " + where(text, pos) +
                           ": the variables are x1..xd, and x, y, z, w when d <= 4");
        uses.push_back({name, pos, alias});
        highest = std::max(highest, i);
      }
      if (p.GetNumResults() != 1)
        throw InputError("',' separates arguments of functions only " + where(text, e.start) +
                         ": separate equations with ';'");
    } catch (const mu::Parser::exception_type& ex) {
      parse_failure(text, e, ex);
    }
  }
  const int d = dim.value_or(std::max(highest, 1));
  check_dimension(d);
  for (const Use& u : uses) {
    bool alias = false;
    if (variable_index(u.name, alias) > d)
      throw InputError("the variable '" + u.name + "' " + where(text, u.position) +
                       " is beyond the dimension d = " + std::to_string(d));
    if (u.alias && d > 4)
      throw InputError("the alias '" + u.name + "' " + where(text, u.position) + " is only for d <= 4: write x1..x" +
                       std::to_string(d));
  }
  const int k = static_cast<int>(equations.size());
  if (max_equations && k > *max_equations)
    throw InputError(std::to_string(k) + " expressions in \"" + std::string(text) + "\", expected " +
                     std::to_string(*max_equations));
  if (!max_equations && k >= d)
    throw InputError(std::to_string(k) + (k == 1 ? " equation" : " equations") + " in R^" + std::to_string(d) + " (\"" +
                     std::string(text) + "\"): a manifold needs fewer equations than the dimension d" +
                     (dim ? "" : "; give --dim D when the variables used do not show d"));

  // Pass 2: the evaluating parsers, bound to x1..xd (and the aliases).
  impl_->d = d;
  impl_->k = k;
  impl_->variables.assign(d, 0.0);
  for (const Equation& e : equations) {
    auto p = std::make_unique<mu::Parser>();
    define_constants(*p);
    for (int i = 0; i < d; ++i) {
      p->DefineVar(std::string("x").append(std::to_string(i + 1)), &impl_->variables[i]);
      if (d <= 4) p->DefineVar(std::string(1, "xyzw"[i]), &impl_->variables[i]);
    }
    try {
      p->SetExpr(e.expr);
      p->Eval();  // parses now, so that errors surface here and not during tracing
    } catch (const mu::Parser::exception_type& ex) {
      parse_failure(text, e, ex);
    }
    impl_->parsers.push_back(std::move(p));
  }
}

ExpressionFunction::~ExpressionFunction() = default;

int ExpressionFunction::ambient_dimension() const { return impl_->d; }
int ExpressionFunction::codimension() const { return impl_->k; }
const std::string& ExpressionFunction::text() const { return impl_->text; }

void ExpressionFunction::evaluate(const double* x, double* value) const {
  std::copy(x, x + impl_->d, impl_->variables.begin());
  for (int j = 0; j < impl_->k; ++j) value[j] = impl_->parsers[j]->Eval();
}

FunctionPtr expression_function(std::string_view equations, std::optional<int> dim) {
  return std::make_shared<const ExpressionFunction>(equations, dim);
}

FunctionPtr expression_domain(std::string_view expression, int dim) {
  return std::make_shared<const ExpressionFunction>(expression, dim, 1);
}

}  // namespace coxmesh
