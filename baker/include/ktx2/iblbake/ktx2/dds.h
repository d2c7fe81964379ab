// The DDS container (Microsoft "Programming Guide for DDS": DDS_HEADER with the DX10 extension
// DDS_HEADER_DXT10) for what iblbake writes as KTX2, as D3D engines and Babylon.js read it: cube maps with
// their mips (DDSCAPS2_CUBEMAP with all six faces, miscFlag D3D11_RESOURCE_MISC_TEXTURECUBE, arraySize the
// number of cubes), 2D images and 2D arrays. The texel bytes are the KTX2 file's (the formats' DXGI twins,
// BC6H blocks as encoded): the file is rewrapped, never re-encoded. Faces in D3D order +X, -X, +Y, -Y, +Z,
// -Z, the images array element by element, face by face, each face's levels largest first. DDS has no
// key/values: what the KTX2 keys say (the storage scale among them) stays in the manifest and the commands'
// output.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace ibl {

// The DDS bytes of a KTX2 file's bytes (validated as readKtx2 does); `name` stands for the file in errors.
std::vector<std::uint8_t> ddsFromKtx2(std::span<const std::uint8_t> ktx2, const std::string& name);

// Reads the KTX2 file `ktx2File` and writes it as DDS to `target` (a plain write: the caller stages it).
void writeDdsFromKtx2(const std::filesystem::path& ktx2File, const std::filesystem::path& target);

} // namespace ibl
