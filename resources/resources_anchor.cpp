// hs_resources has no code of its own; the compiled Qt resources hang off it.
namespace hs::resources {
int anchor() { return 0; }
}  // namespace hs::resources
