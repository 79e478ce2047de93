#include "program/program_parser.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/core.h>

#include "core/source_place.hpp"
#include "core/ascii.hpp"
#include "core/json_reader.hpp"
#include "motion/kinematics.hpp"
#include "files/language_words.hpp"
#include "files/points_file.hpp"
#include "program/program_lexer.hpp"

namespace armctl::program {

namespace {

// What may follow each move (docs/programs.md "Moves").
constexpr std::string_view kPtpOptions = "speed=N% and accel=N% (of the joints' limits)";
constexpr std::string_view kPathOptions = "speed=, accel=, angular_speed=, zone=";
constexpr std::string_view kStatements =
    "a statement: PTP, LIN, CIRC, WAIT, GRIPPER, PRINT, IF, LOOP, WHILE, CALL, OVERRIDE, DEF or NAME = value";

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::string_view source) : t_(std::move(tokens)), source_(source) {}

  Program program() {
    Program p;
    p.source = std::string(source_);
    for (;;) {
      skip_newlines();
      if (peek().kind == TokenKind::end_of_file) break;
      if (word_is(peek(), "def")) {
        Subroutine s = subroutine();
        for (const auto& other : p.subroutines)
          if (other.name == s.name)
            fail_at(s.at, s.name, fmt::format("each subroutine name once ('{}' is defined at line {})", s.name, other.at.line));
        p.subroutines.push_back(std::move(s));
      } else {
        p.main.push_back(statement(0));
      }
    }
    return p;
  }

 private:
  // ---- tokens
  const Token& peek(std::size_t ahead = 0) const { return t_[std::min(k_ + ahead, t_.size() - 1)]; }
  const Token& next() {
    const Token& t = t_[k_];
    if (k_ + 1 < t_.size()) ++k_;
    return t;
  }
  static bool word_is(const Token& t, std::string_view w) { return t.kind == TokenKind::name && ascii_lower(t.text) == w; }
  static bool symbol_is(const Token& t, std::string_view s) { return t.kind == TokenKind::symbol && t.text == s; }
  void skip_newlines() {
    while (peek().kind == TokenKind::newline) next();
  }

  [[noreturn]] void fail(const Token& t, std::string_view expected) const {
    throw ArmctlError(source_error(ErrorKind::invalid_config, {std::string(source_), t.at.line, t.at.column,
                                                               fmt::format("found {}, expected {}", describe(t), expected)}));
  }
  [[noreturn]] void fail_at(Place at, std::string_view found, std::string_view expected) const {
    throw ArmctlError(source_error(ErrorKind::invalid_config, {std::string(source_), at.line, at.column,
                                                               fmt::format("found '{}', expected {}", found, expected)}));
  }
  void expect_symbol(std::string_view s, std::string_view expected) {
    if (!symbol_is(peek(), s)) fail(peek(), expected);
    next();
  }
  void end_of_statement(std::string_view what) {
    if (peek().kind != TokenKind::newline) fail(peek(), fmt::format("the end of the line after {}", what));
    next();
  }
  // A name the user chose (a point, variable, subroutine or parameter).
  std::string user_name(std::string_view what) {
    const Token& t = peek();
    if (t.kind != TokenKind::name) fail(t, what);
    if (auto why = files::bad_name(t.text)) fail(t, fmt::format("{} ({})", what, *why));
    next();
    return t.text;
  }

  // ---- subroutines and blocks
  Subroutine subroutine() {
    Subroutine s;
    s.at = next().at;  // def
    s.name = user_name("the subroutine's name after DEF (e.g. DEF pick(height))");
    expect_symbol("(", "'(' and the parameters after the subroutine's name (DEF name() for none)");
    if (!symbol_is(peek(), ")")) {
      for (;;) {
        const Token& at = peek();
        std::string p = user_name("a parameter name");
        if (std::find(s.parameters.begin(), s.parameters.end(), p) != s.parameters.end())
          fail(at, "each parameter name once");
        s.parameters.push_back(std::move(p));
        if (!symbol_is(peek(), ",")) break;
        next();
      }
    }
    expect_symbol(")", "',' and another parameter, or ')'");
    end_of_statement("DEF name(...)");
    s.body = block(1, {"end"}, "END to close the DEF at line " + std::to_string(s.at.line));
    next();  // end
    end_of_statement("END");
    return s;
  }

  // Statements up to one of `closers` (not consumed).
  Block block(std::size_t depth, std::initializer_list<std::string_view> closers, const std::string& missing) {
    if (depth > kProgramMaxNesting) fail(peek(), fmt::format("at most {} IF/LOOP/WHILE inside one another", kProgramMaxNesting));
    Block b;
    for (;;) {
      skip_newlines();
      const Token& t = peek();
      if (t.kind == TokenKind::end_of_file) fail(t, missing);
      for (auto c : closers)
        if (word_is(t, c)) return b;
      if (word_is(t, "def")) fail(t, "a statement (a DEF belongs outside any other block: " + missing + " first)");
      b.push_back(statement(depth));
    }
  }

  // ---- statements
  Statement statement(std::size_t depth) {
    const Token& t = peek();
    Statement s;
    s.at = t.at;
    if (t.kind != TokenKind::name) fail(t, kStatements);
    const std::string w = ascii_lower(t.text);
    if (w == "ptp" || w == "lin" || w == "circ") {
      move(s, w);
      return s;
    }
    if (w == "wait") {
      next();
      s.kind = StatementKind::wait;
      s.value = expression("a time after WAIT (e.g. WAIT 0.5s)");
      end_of_statement("WAIT time");
    } else if (w == "gripper") {
      next();
      s.kind = StatementKind::gripper;
      if (word_is(peek(), "open")) {
        next();
        s.gripper = GripperAction::open;
      } else if (word_is(peek(), "close")) {
        next();
        s.gripper = GripperAction::close;
      } else {
        s.gripper = GripperAction::to;
        s.value = expression("OPEN, CLOSE or how far closed (e.g. GRIPPER 40%) after GRIPPER");
      }
      end_of_statement("GRIPPER ...");
    } else if (w == "print") {
      next();
      s.kind = StatementKind::print;
      for (;;) {
        PrintItem item;
        if (peek().kind == TokenKind::string) item.text = next().text;
        else item.value = expression("a \"text\" or a value to PRINT");
        s.print.push_back(std::move(item));
        if (!symbol_is(peek(), ",")) break;
        next();
      }
      end_of_statement("PRINT ...");
    } else if (w == "if") {
      next();
      s.kind = StatementKind::if_;
      s.value = expression("a condition after IF (e.g. IF n > 2 THEN)");
      if (word_is(peek(), "then")) next();
      end_of_statement("IF condition [THEN]");
      const std::string missing = fmt::format("ELSE or END to close the IF at line {}", s.at.line);
      s.body = block(depth + 1, {"else", "end"}, missing);
      if (word_is(peek(), "else")) {
        next();
        end_of_statement("ELSE");
        s.otherwise = block(depth + 1, {"end"}, fmt::format("END to close the IF at line {}", s.at.line));
      }
      next();
      end_of_statement("END");
    } else if (w == "loop") {
      next();
      s.kind = StatementKind::loop;
      s.value = expression("a count after LOOP (e.g. LOOP 3 TIMES)");
      if (!word_is(peek(), "times")) fail(peek(), "TIMES after the count (LOOP 3 TIMES)");
      next();
      end_of_statement("LOOP count TIMES");
      s.body = block(depth + 1, {"end"}, fmt::format("END to close the LOOP at line {}", s.at.line));
      next();
      end_of_statement("END");
    } else if (w == "while") {
      next();
      s.kind = StatementKind::while_;
      s.value = expression("a condition after WHILE (e.g. WHILE n < 3)");
      end_of_statement("WHILE condition");
      s.body = block(depth + 1, {"end"}, fmt::format("END to close the WHILE at line {}", s.at.line));
      next();
      end_of_statement("END");
    } else if (w == "call") {
      next();
      s.kind = StatementKind::call;
      s.name = user_name("the subroutine's name after CALL");
      expect_symbol("(", "'(' and the arguments after the subroutine's name (CALL name() for none)");
      if (!symbol_is(peek(), ")")) {
        for (;;) {
          s.arguments.push_back(expression("an argument"));
          if (!symbol_is(peek(), ",")) break;
          next();
        }
      }
      expect_symbol(")", "',' and another argument, or ')'");
      end_of_statement("CALL name(...)");
    } else if (w == "override") {
      next();
      s.kind = StatementKind::override_;
      s.value = expression("a percentage after OVERRIDE (e.g. OVERRIDE 50%)");
      end_of_statement("OVERRIDE percentage");
    } else if (symbol_is(peek(1), "=")) {
      s.kind = StatementKind::assign;
      s.name = user_name("a variable name before '='");
      next();  // =
      s.value = expression("a value after '='");
      end_of_statement("NAME = value");
    } else {
      fail(t, kStatements);
    }
    return s;
  }

  void move(Statement& s, const std::string& w) {
    next();
    s.kind = StatementKind::move;
    s.move = w == "ptp" ? MoveKind::ptp : w == "lin" ? MoveKind::lin : MoveKind::circ;
    if (s.move == MoveKind::circ) {
      s.via = target("the CIRC's via point: a point name, pose(...) or joints(...) (CIRC via, target)");
      expect_symbol(",", "',' and the CIRC's target after its via point (CIRC via, target)");
    }
    s.target = target(fmt::format("the {}'s target: a point name, pose(x=.., y=.., z=..) or joints(..)", to_string(s.move)));
    const std::string_view allowed = s.move == MoveKind::ptp ? kPtpOptions : kPathOptions;
    while (peek().kind == TokenKind::name) {
      Field f;
      f.at = peek().at;
      f.name = ascii_lower(peek().text);
      const bool ok = s.move == MoveKind::ptp ? (f.name == "speed" || f.name == "accel")
                                              : (f.name == "speed" || f.name == "accel" || f.name == "angular_speed" ||
                                                 f.name == "zone");
      if (!ok) fail(peek(), fmt::format("an option of {}: {}", to_string(s.move), allowed));
      for (const auto& o : s.options)
        if (o.name == f.name) fail(peek(), "each option once per move");
      next();
      expect_symbol("=", fmt::format("'=' and a value after {}", f.name));
      f.value = expression(fmt::format("a value for {}", f.name));
      s.options.push_back(std::move(f));
    }
    end_of_statement(fmt::format("the {} (options: {})", to_string(s.move), allowed));
  }

  Target target(const std::string& what) {
    Target t;
    t.at = peek().at;
    if (word_is(peek(), "pose")) {
      next();
      t.kind = TargetKind::pose;
      t.pose = fields("pose", {"x", "y", "z", "roll", "pitch", "yaw", "elbow"});
      bool xyz[3] = {};
      for (const auto& f : t.pose)
        if (f.name.size() == 1 && f.name[0] >= 'x' && f.name[0] <= 'z') xyz[f.name[0] - 'x'] = true;
      for (int k = 0; k < 3; ++k)
        if (!xyz[k]) fail_at(t.at, "pose(...)", fmt::format("x, y and z in a pose ({} is missing)", "xyz"[k]));
    } else if (word_is(peek(), "joints")) {
      next();
      t.kind = TargetKind::joints;
      expect_symbol("(", "'(' and one value per joint after joints (e.g. joints(0deg, 30deg, -45deg))");
      for (;;) {
        t.joints.push_back(expression("a joint value (e.g. 30deg, 120mm)"));
        if (!symbol_is(peek(), ",")) break;
        next();
      }
      expect_symbol(")", "',' and another joint value, or ')'");
    } else {
      if (peek().kind != TokenKind::name || files::is_language_word(peek().text)) fail(peek(), what);
      t.kind = TargetKind::point;
      t.point = user_name(what);
    }
    if (symbol_is(peek(), "+")) {
      next();
      if (word_is(peek(), "tool")) t.offset_frame = OffsetFrame::tool;
      else if (word_is(peek(), "base")) t.offset_frame = OffsetFrame::base;
      else fail(peek(), "tool(...) or base(...) after '+': an offset in the tool's or the base's frame");
      const std::string frame = ascii_lower(peek().text);
      next();
      t.offset = fields(frame, {"x", "y", "z"});
    }
    return t;
  }

  // (name=value, ...) with names from `allowed`, each once.
  std::vector<Field> fields(const std::string& what, std::initializer_list<std::string_view> allowed) {
    std::string names;
    for (auto a : allowed) names += (names.empty() ? "" : ", ") + std::string(a);
    expect_symbol("(", fmt::format("'(' after {} and its fields ({})", what, names));
    std::vector<Field> out;
    if (symbol_is(peek(), ")")) fail(peek(), fmt::format("a field of {}: {}", what, names));
    for (;;) {
      Field f;
      f.at = peek().at;
      f.name = peek().kind == TokenKind::name ? ascii_lower(peek().text) : "";
      if (std::find(allowed.begin(), allowed.end(), f.name) == allowed.end())
        fail(peek(), fmt::format("a field of {}: {}", what, names));
      for (const auto& o : out)
        if (o.name == f.name) fail(peek(), fmt::format("each field of {} once", what));
      next();
      expect_symbol("=", fmt::format("'=' and a value after {}", f.name));
      if (f.name == "elbow") {
        const Token& e = peek();
        const std::string v = e.kind == TokenKind::name ? ascii_lower(e.text) : "";
        if (!motion::parse_elbow(v)) fail(e, "elbow up or down (xArm), left or right (SCARA)");
        f.word = v;
        next();
      } else {
        f.value = expression(fmt::format("a value for {}", f.name));
      }
      out.push_back(std::move(f));
      if (!symbol_is(peek(), ",")) break;
      next();
    }
    expect_symbol(")", fmt::format("',' and another field of {}, or ')'", what));
    return out;
  }

  // ---- expressions: or < and < not < comparison < + - < * / < unary - < primary
  ExprPtr expression(const std::string& what) {
    what_ = &what;
    depth_ = 0;
    operators_ = 0;
    return or_expr();
  }
  // Counts the binary operators of the expression as they are read, before their right
  // side is: `at` is the operator's place.
  void count_operator(Place at, std::string_view op) {
    if (++operators_ > kExpressionMaxOperators)
      fail_at(at, op, fmt::format("at most {} operators in one expression (split it: give parts of it to variables)",
                                  kExpressionMaxOperators));
  }
  ExprPtr binary(Operator op, Place at, ExprPtr l, ExprPtr r) {
    auto e = std::make_unique<Expr>();
    e->kind = ExprKind::binary;
    e->op = op;
    e->at = at;
    e->left = std::move(l);
    e->right = std::move(r);
    return e;
  }
  ExprPtr or_expr() {
    ExprPtr l = and_expr();
    while (word_is(peek(), "or")) {
      const Place at = next().at;
      count_operator(at, "or");
      l = binary(Operator::or_, at, std::move(l), and_expr());
    }
    return l;
  }
  ExprPtr and_expr() {
    ExprPtr l = not_expr();
    while (word_is(peek(), "and")) {
      const Place at = next().at;
      count_operator(at, "and");
      l = binary(Operator::and_, at, std::move(l), not_expr());
    }
    return l;
  }
  ExprPtr not_expr() {
    if (word_is(peek(), "not")) {
      guard(peek());
      const Place at = next().at;
      auto e = std::make_unique<Expr>();
      e->kind = ExprKind::unary;
      e->op = Operator::not_;
      e->at = at;
      e->left = not_expr();
      --depth_;
      return e;
    }
    return comparison();
  }
  ExprPtr comparison() {
    ExprPtr l = additive();
    static const std::pair<std::string_view, Operator> kOps[] = {{"<", Operator::lt},  {"<=", Operator::le},
                                                                 {">", Operator::gt},  {">=", Operator::ge},
                                                                 {"==", Operator::eq}, {"!=", Operator::ne}};
    for (auto [text, op] : kOps)
      if (symbol_is(peek(), text)) {
        const Place at = next().at;
        count_operator(at, text);
        return binary(op, at, std::move(l), additive());
      }
    return l;
  }
  ExprPtr additive() {
    ExprPtr l = multiplicative();
    while (symbol_is(peek(), "+") || symbol_is(peek(), "-")) {
      // "p + tool(...)" is an offset, not arithmetic: expressions never hold a target.
      if (word_is(peek(1), "tool") || word_is(peek(1), "base")) break;
      const Token& t = next();
      count_operator(t.at, t.text);
      l = binary(t.text == "+" ? Operator::add : Operator::sub, t.at, std::move(l), multiplicative());
    }
    return l;
  }
  ExprPtr multiplicative() {
    ExprPtr l = unary();
    while (symbol_is(peek(), "*") || symbol_is(peek(), "/")) {
      const Token& t = next();
      count_operator(t.at, t.text);
      l = binary(t.text == "*" ? Operator::mul : Operator::div, t.at, std::move(l), unary());
    }
    return l;
  }
  ExprPtr unary() {
    if (symbol_is(peek(), "-")) {
      guard(peek());
      const Place at = next().at;
      auto e = std::make_unique<Expr>();
      e->kind = ExprKind::unary;
      e->op = Operator::neg;
      e->at = at;
      e->left = unary();
      --depth_;
      return e;
    }
    return primary();
  }
  ExprPtr primary() {
    const Token& t = peek();
    auto e = std::make_unique<Expr>();
    e->at = t.at;
    if (t.kind == TokenKind::number) {
      e->kind = ExprKind::number;
      e->value = t.value;
      next();
      return e;
    }
    if (t.kind == TokenKind::name && !files::is_language_word(t.text)) {
      e->kind = ExprKind::variable;
      e->name = user_name(*what_);
      return e;
    }
    if (symbol_is(t, "(")) {
      guard(t);
      next();
      ExprPtr inner = or_expr();
      --depth_;
      expect_symbol(")", "')' to close the '('");
      return inner;
    }
    fail(t, *what_ + " (a number with its unit, a variable or '(')");
  }
  // Deeply nested input must not exhaust the stack (the parser recurses per level, and so
  // do the evaluator and the tree's destructor).
  void guard(const Token& opener) {
    if (++depth_ > kExpressionMaxNesting)
      fail(opener, fmt::format("at most {} parentheses, signs and NOTs inside one another", kExpressionMaxNesting));
  }

  std::vector<Token> t_;
  std::size_t k_ = 0;
  std::string_view source_;
  const std::string* what_ = nullptr;
  int depth_ = 0;
  int operators_ = 0;
};

}  // namespace

Expr::~Expr() {
  if (!left && !right) return;
  std::vector<ExprPtr> pending;
  auto take = [&](ExprPtr& child) {
    if (child) pending.push_back(std::move(child));
  };
  take(left);
  take(right);
  while (!pending.empty()) {
    ExprPtr e = std::move(pending.back());
    pending.pop_back();
    take(e->left);
    take(e->right);
  }  // e goes here, its children already taken
}

const char* to_string(Operator op) {
  switch (op) {
    case Operator::add: return "+";
    case Operator::sub: return "-";
    case Operator::mul: return "*";
    case Operator::div: return "/";
    case Operator::neg: return "-";
    case Operator::lt: return "<";
    case Operator::le: return "<=";
    case Operator::gt: return ">";
    case Operator::ge: return ">=";
    case Operator::eq: return "==";
    case Operator::ne: return "!=";
    case Operator::and_: return "and";
    case Operator::or_: return "or";
    case Operator::not_: return "not";
  }
  return "?";
}

const char* to_string(MoveKind kind) {
  switch (kind) {
    case MoveKind::ptp: return "PTP";
    case MoveKind::lin: return "LIN";
    case MoveKind::circ: return "CIRC";
  }
  return "?";
}

Result<Program> parse_program(std::string_view text, std::string_view source) {
  if (text.size() > kProgramMaxBytes)
    return Error{ErrorKind::invalid_config, fmt::format("{}: {} bytes; a program has at most {}", source, text.size(), kProgramMaxBytes)};
  auto tokens = lex_program(text, source);
  if (!tokens) return tokens.error();
  return catch_error([&]() -> Result<Program> { return Parser(std::move(tokens).value(), source).program(); });
}

Result<Program> read_program_file(const std::filesystem::path& path) {
  auto text = catch_error([&]() -> Result<std::string> { return json_reader::read_config_file(path, "program"); });
  if (!text) return text.error();
  return parse_program(*text, path.string());
}

}  // namespace armctl::program
