#pragma once
// The shape every Lua binding shares (one bind_<type>.cpp per exposed C++ type):
//
//   INVASIM_LUA_TYPE(Progress, "Progress");   // LuaType<Progress>: names and __tostring
//   std::string LuaType<Progress>::describe(const Progress& p) { ... }
//   int l_update(lua_State* L) { check<Progress>(L, 1).update(...); return 0; }  // may throw
//   define_type<Progress>(L, {{"update", &lua_wrap<&l_update>}});  // when the module opens
//   push(L, std::make_shared<Progress>(...));             // from a constructor
//
// Error discipline. Debian's Lua is built as C, so lua_error/luaL_error longjmp: a Lua error
// raised while a C++ object with a destructor is alive in the frames it unwinds skips that
// destructor (and leaks what it owns). Hence:
// - code inside an l_ function never calls luaL_check*, luaL_error or lua_error; it throws
//   C++ exceptions (InputError), and lua_wrap turns them into a Lua error "file:line: message"
//   after every C++ object is gone;
// - every Lua API call that can raise (anything that allocates: lua_pushstring, lua_createtable,
//   lua_setfield, lua_rawseti, lua_newuserdatauv, ...; a memory error is a Lua error) runs
//   inside protected_call(): a noexcept lambda run under lua_pcall, whose frame owns nothing,
//   and whose failure comes back as a C++ exception that unwinds the C++ frames normally. Calls
//   that never raise (lua_pushnumber, lua_pushinteger, lua_pushvalue, lua_rawget, lua_type,
//   lua_to* on the right type, lua_pop) may be made anywhere; a raising call outside
//   protected_call() is allowed only in a frame (and its callers up to lua_wrap) that owns no C++
//   object with a destructor (references into userdata and plain values only);
// - Lua callbacks from C++ go through call_lua(), which uses lua_pcall and rethrows as a C++
//   exception.
#include <lua.hpp>

#include <algorithm>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace invasim::lua {

// Type name of the value at index: "number", "string", a bound type's short name
// ("Progress" for invasim.Progress userdata), or "no value".
std::string type_name_at(lua_State* L, int index);

// Pushes a string (protected: may be called anywhere); adapters.hpp's push_value overloads.
void push_value(lua_State* L, const std::string& v);

// Per-type names and description; specialised next to each binding.
template <typename T>
struct LuaType;

// Specialises LuaType<T> with the Lua name NAME (metatable "invasim.NAME"); its describe(), the
// __tostring text, is defined next to the binding.
#define INVASIM_LUA_TYPE(T, NAME)                             \
  template <>                                                 \
  struct LuaType<T> {                                         \
    static constexpr const char* name = NAME;                 \
    static constexpr const char* metatable = "invasim." NAME; \
    static std::string describe(const T& object);             \
  }

// A C++ exception that already carries a complete Lua error message (with its location),
// e.g. from a failed Lua callback: lua_wrap re-raises it as is, whole (message() keeps a NUL
// that would end what()).
class LuaRaised : public std::runtime_error {
 public:
  explicit LuaRaised(const std::string& message) : std::runtime_error(message), message_(message) {}
  const std::string& message() const { return message_; }

 private:
  std::string message_;
};

// Thrown by a binding to stop the script quietly (`invasim params` stops at invasim.params):
// lua_wrap raises the stop sentinel instead of an error message, and LuaState::run_file
// reports Outcome::kStopped.
class StopScript {};

// The stop sentinel (a light userdata) and its test.
void push_stop_sentinel(lua_State* L);
bool is_stop_sentinel(lua_State* L, int index);

// Pushes "file:line: " of the innermost Lua function on the call stack (skipping C functions
// such as pcall), or "" when there is none. Never raises.
void push_where(lua_State* L);

// "bad argument #2 to 'update' (number expected, got string)"-style text for argument `arg`
// of the running C function; `expected` names the wanted type, `got` the value (default: its
// type).
std::string bad_argument(lua_State* L, int arg, const std::string& expected,
                         const std::string& got = "");

// Refuses a value given after the `count` arguments a function takes (trailing nils pass), as
// an unknown keyword is refused: "bad argument #2 to 'compute' (no value expected, got table)".
void no_arguments_after(lua_State* L, int count);

// Calls the function below `nargs` arguments on the stack with lua_pcall; a Lua error comes
// back as LuaRaised (a string message kept as is, any other error object described with the
// place it was raised: lua/error_object.hpp), so it unwinds C++ frames cleanly.
void call_lua(lua_State* L, int nargs, int nresults);

// Thrown when a protected_call() block failed with a Lua error other than a runtime error (e.g.
// LUA_ERRMEM "not enough memory"): lua_wrap adds the script location.
class LuaApiError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {

// lua_pcall'd by protected_call(): runs the lambda whose address is argument 1 on the arguments
// after it. The lambda is noexcept and its frame owns no C++ object, so a Lua error raised in
// it (a longjmp to the lua_pcall) skips no destructor.
template <typename Fn>
int run_protected(lua_State* L) {
  Fn& fn = *static_cast<Fn*>(lua_touserdata(L, 1));
  lua_remove(L, 1);
  return fn(L);
}

// Pops the error object of a failed protected call and throws it as a C++ exception
// (LuaRaised for a runtime error with its location, LuaApiError otherwise).
[[noreturn]] void throw_protected_error(lua_State* L, int status);

}  // namespace detail

// Runs fn(L) under lua_pcall with the `nargs` values on top of the stack as its arguments
// (indices 1..nargs inside fn) and leaves `nresults` of the values fn returns (`return n`, as
// a lua_CFunction) on the stack. fn must be a noexcept lambda that makes Lua API calls only
// (reading captured C++ data by reference is fine; creating C++ objects is not). A Lua error in
// it (out of memory) becomes a C++ exception here, after the pcall, so C++ frames unwind.
template <typename Fn>
void protected_call(lua_State* L, int nargs, int nresults, Fn&& fn) {
  using F = std::remove_reference_t<Fn>;
  static_assert(std::is_nothrow_invocable_r_v<int, F&, lua_State*>,
                "protected_call needs a noexcept lambda (lua_State*) -> int");
  if (!lua_checkstack(L, 2 + (nresults > 0 ? nresults : 0)))  // never raises
    throw LuaApiError("Lua stack overflow");
  lua_pushcfunction(L, &detail::run_protected<F>);  // a light C function: no allocation
  lua_pushlightuserdata(L, static_cast<void*>(&fn));
  lua_rotate(L, -(nargs + 2), 2);
  const int status = lua_pcall(L, nargs + 1, nresults, 0);
  if (status != LUA_OK) detail::throw_protected_error(L, status);
}

// The usual case: fn pushes the binding's results; returns their number for `return`.
template <typename Fn>
int push_results(lua_State* L, int nresults, Fn&& fn) {
  protected_call(L, 0, nresults, std::forward<Fn>(fn));
  return nresults;
}

// Positional arguments of methods, checked without luaL_check* (which would longjmp): they
// throw InputError("bad argument #2 to 'update' (number expected, got string)").
double arg_number(lua_State* L, int index);
// An integer argument in [lo, hi], checked before any narrowing: "bad argument #2 to 'run'
// (integer >= 0 expected, got -1)".
long long arg_integer(lua_State* L, int index, long long lo, long long hi);
std::string arg_string(lua_State* L, int index);
// A string argument naming a file or directory: a NUL byte in it is refused (the system call
// would stop there, at another path).
std::string arg_path(lua_State* L, int index);
// The same refusal for a path given as a key ("Snapshots: key 'dir'"), naming it.
void require_no_nul(const std::string& path, const std::string& what);
std::optional<double> opt_number(lua_State* L, int index);  // nil or absent -> nullopt

// Wraps an l_ function: C++ exceptions become Lua errors with the caller's file:line. The
// message is copied into a fixed buffer inside the catch block (no allocation that could
// longjmp there), and lua_error is raised only after the catch block has ended.
template <int (*F)(lua_State*)>
int lua_wrap(lua_State* L) {
  constexpr std::size_t kMax = 4096;
  char message[kMax];
  std::size_t length = 0;  // of a LuaRaised message (NULs included); else up to the first NUL
  bool has_location = false;
  bool stop = false;
  try {
    return F(L);
  } catch (const StopScript&) {
    stop = true;
  } catch (const LuaRaised& e) {
    length = std::min(e.message().size(), kMax - 1);
    std::memcpy(message, e.message().data(), length);
    has_location = true;
  } catch (const std::exception& e) {
    std::strncpy(message, e.what(), kMax - 1);
  } catch (...) {
    std::strncpy(message, "unknown C++ exception", kMax - 1);
  }
  if (stop) {
    push_stop_sentinel(L);
    return lua_error(L);
  }
  message[kMax - 1] = '\0';
  if (has_location)
    lua_pushlstring(L, message, length);
  else {
    push_where(L);
    lua_pushstring(L, message);
    lua_concat(L, 2);
  }
  return lua_error(L);
}

// --- Type tags ---
// A bound object's userdata is [TypeTag pointer][nullptr][std::shared_ptr<T>]: the tag names
// the C++ type stored in it and is checked on every access (check, test, __gc, __tostring).
// The metatable is not trusted for that, since debug.setmetatable can swap it. The nullptr
// at offset 8 makes the block read as a closed file to Lua's io library should a script give
// a bound object the FILE* metatable (io then refuses it instead of using the tag as a FILE*).

// Identifies one bound C++ type; `destroy` resets the shared_ptr stored in a payload.
struct TypeTag {
  const char* name;
  void (*destroy)(void* payload) noexcept;
};

namespace detail {

struct UserdataHeader {
  const TypeTag* tag;
  void* closed_file;  // always nullptr (see above)
};
constexpr std::size_t kPayloadOffset = sizeof(UserdataHeader);
constexpr std::size_t kUserdataSize = kPayloadOffset + sizeof(std::shared_ptr<void>);

template <typename T>
void destroy_payload(void* payload) noexcept {
  auto* slot = static_cast<std::shared_ptr<T>*>(payload);
  slot->~shared_ptr();
  new (slot) std::shared_ptr<T>();  // a resurrected userdata reads as "no longer valid"
}

template <typename T>
inline constexpr TypeTag kTypeTag{LuaType<T>::name, &destroy_payload<T>};

// Adds a tag to the set tag_at() accepts (define_type does it). Thread-safe.
void register_tag(const TypeTag* tag);

// The tag of the bound object at `index`, or nullptr if the value is anything else (not a full
// userdata, a userdata of another size, or one whose first word is no registered tag).
const TypeTag* tag_at(lua_State* L, int index);

// The payload (the shared_ptr's address) of the bound object at `index` if it holds a T.
template <typename T>
std::shared_ptr<T>* test_slot(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TUSERDATA || lua_rawlen(L, index) != kUserdataSize) return nullptr;
  auto* block = static_cast<unsigned char*>(lua_touserdata(L, index));
  UserdataHeader header;
  std::memcpy(&header, block, sizeof header);
  if (header.tag != &kTypeTag<T>) return nullptr;
  return std::launder(reinterpret_cast<std::shared_ptr<T>*>(block + kPayloadOffset));
}

// "bad argument #1 to 'f' (System expected, got Contacts)" and the method-call hints.
std::string wrong_type_message(lua_State* L, int index, const char* expected);

}  // namespace detail

// The shared_ptr held by the userdata at `index`; throws InputError if the value is not a T
// (by its type tag) or the object was already collected.
template <typename T>
std::shared_ptr<T>& check_shared(lua_State* L, int index) {
  auto* slot = detail::test_slot<T>(L, index);
  if (slot == nullptr) throw InputError(detail::wrong_type_message(L, index, LuaType<T>::name));
  if (!*slot) throw InputError(std::string(LuaType<T>::name) + " object is no longer valid");
  return *slot;
}

// The T held by the userdata at `index` (see check_shared).
template <typename T>
T& check(lua_State* L, int index) {
  return *check_shared<T>(L, index);
}

// The shared_ptr held by the value at `index` if it is a T (by its type tag), else nullptr;
// an empty shared_ptr (collected object) is returned as is. Never raises.
template <typename T>
std::shared_ptr<T>* test(lua_State* L, int index) {
  return detail::test_slot<T>(L, index);
}

// Whether the value at `index` is a bound T (by its type tag).
template <typename T>
bool is(lua_State* L, int index) {
  return detail::test_slot<T>(L, index) != nullptr;
}

// Pushes a new userdata holding `object` (tag, then placement new of the shared_ptr) with T's
// metatable. The object moves into the userdata only once its memory exists: if the allocation
// fails, it is still owned by `object`, which C++ unwinding destroys.
template <typename T>
void push(lua_State* L, std::shared_ptr<T> object) {
  static_assert(sizeof(std::shared_ptr<T>) == sizeof(std::shared_ptr<void>));
  if (!object) throw std::logic_error(std::string("push of a null ") + LuaType<T>::name);
  std::shared_ptr<T>* source = &object;
  protected_call(L, 0, 1, [source](lua_State* S) noexcept {
    auto* block = static_cast<unsigned char*>(lua_newuserdatauv(S, detail::kUserdataSize, 0));
    const detail::UserdataHeader header{&detail::kTypeTag<T>, nullptr};
    std::memcpy(block, &header, sizeof header);
    new (block + detail::kPayloadOffset) std::shared_ptr<T>(std::move(*source));
    luaL_setmetatable(S, LuaType<T>::metatable);  // the registered name: no allocation
    return 1;
  });
}

namespace detail {

// __gc of every bound type: destroys the shared_ptr of the type its tag names (whatever the
// metatable says), leaving an empty one in its place.
int gc(lua_State* L);

template <typename T>
int tostring(lua_State* L) {
  auto* slot = test_slot<T>(L, 1);
  const TypeTag* tag = tag_at(L, 1);
  std::string text = "userdata";  // our metatable on a foreign userdata (debug.setmetatable)
  if (slot)
    text = *slot ? LuaType<T>::describe(**slot) : std::string(tag->name) + " (no longer valid)";
  else if (tag)
    text = std::string(tag->name) + " (with the metatable of a " + LuaType<T>::name + ")";
  push_value(L, text);
  return 1;
}

// Builds the metatable `name` with the methods table (upvalue of __index); `type_name` is used
// in the "has no method" error. Defined in binding.cpp.
void define_metatable(lua_State* L, const char* name, const char* type_name,
                      const luaL_Reg* methods, lua_CFunction gc, lua_CFunction tostring);

}  // namespace detail

// Registers T's metatable: methods (already wrapped with lua_wrap), __gc, __tostring, an
// __index that names the valid methods on a typo, and a locked __metatable.
template <typename T>
void define_type(lua_State* L, const luaL_Reg* methods) {
  detail::register_tag(&detail::kTypeTag<T>);
  detail::define_metatable(L, LuaType<T>::metatable, LuaType<T>::name, methods, &detail::gc,
                           &lua_wrap<&detail::tostring<T>>);
}

// A list of functions as luaL_setfuncs takes it (ending in {nullptr, nullptr}), built from
// lists written in place. A plain array, so it has no destructor for a Lua error to skip.
inline constexpr std::size_t kMaxMethods = 64;
class RegList {
 public:
  RegList(std::initializer_list<luaL_Reg> entries) {
    for (const luaL_Reg& r : entries) add(r);
  }
  void add(const luaL_Reg& r) {
    if (n_ >= kMaxMethods)
      throw std::logic_error("a binding lists more than kMaxMethods functions");
    list_[n_++] = r;
    list_[n_] = {nullptr, nullptr};
  }
  const luaL_Reg* data() const { return list_; }

 private:
  luaL_Reg list_[kMaxMethods + 1] = {{nullptr, nullptr}};
  std::size_t n_ = 0;
};

// The same with the method list written in place (no terminating {nullptr, nullptr}):
//   define_type<Group>(L, {getter<Group, ...>("size"), {"name", &lua_wrap<&l_name>}});
template <typename T>
void define_type(lua_State* L, std::initializer_list<luaL_Reg> methods) {
  define_type<T>(L, RegList(methods).data());
}

// {"name", &lua_wrap<&l_name>}: the list entry of a binding's function l_<name> under its own
// name, so that the name is written once: define_type<T>(L, {INVASIM_LUA_FN(run), ...}).
#define INVASIM_LUA_FN(name)                      \
  luaL_Reg {                                      \
#name, &::invasim::lua::lua_wrap < &l_##name> \
  }

// Sets each function of the list (already wrapped with lua_wrap) as a field of the table on top
// of the stack, the module table when a bind_<part>.cpp opens:
//   add_functions(L, {{"write_file", &lua_wrap<&l_write_file>}, {"exists", ...}});
void add_functions(lua_State* L, std::initializer_list<luaL_Reg> functions);

// Pushes the list {item 0, ..., item n-1}, where push_item(k) pushes item k. It allocates: call
// it inside a protected_call block, or from a frame that owns no C++ object (see above).
template <typename PushItem>
void push_list(lua_State* L, std::size_t n, PushItem&& push_item) {
  lua_createtable(L, n < 0x7fffffff ? static_cast<int>(n) : 0, 0);
  for (std::size_t k = 0; k < n; ++k) {
    push_item(k);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
}

// __pairs of a read-only proxy table: iterates, with raw access, the table it hides (its
// upvalue 1), whatever the script did to the global `next`. Plain C-style code (may raise).
int hidden_table_pairs(lua_State* L);

// Pushes a list of strings (protected: may be called anywhere).
void push_string_list(lua_State* L, const std::vector<std::string>& items);

}  // namespace invasim::lua
