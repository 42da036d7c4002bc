// Byte-for-byte equality of two arrays, for tests that require identical
// results (the same BVH from every thread count or rank, the same pixels
// from every render path). Element types must have no padding bytes left
// unwritten (WideBvhNode and TrianglePacket: their static_asserts fix the
// layout). Any allocator (MeshAccel's arrays use HugePageAllocator).
#pragma once

#include <cstring>
#include <vector>

namespace rayform::test {

template <class T, class A>
bool same_bytes(const std::vector<T, A>& a, const std::vector<T, A>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace rayform::test
