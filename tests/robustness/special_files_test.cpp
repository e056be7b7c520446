// Scenes that name something other than a regular file — a FIFO nobody writes to, a device,
// a directory — as the scene itself, a .mtl library, a texture, a glTF buffer or image. Opening
// a FIFO for reading blocks until a writer appears, so a loader that opens whatever it is
// given hangs; every case here must end quickly with a message naming what is wrong.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "process.h"

namespace gc::test {
namespace {

const char* k_triangle_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// The bad corpus's valid glTF triangle (its buffer is tri_ok.bin), with `buffer_uri` and an
// optional base-colour image `image_uri`.
std::string triangle_gltf(const std::string& buffer_uri, const std::string& image_uri)
{
    std::string doc = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
                      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1)";
    doc += image_uri.empty() ? "}]}]," : R"(,"material":0}]}],"materials":[{"pbrMetallicRoughness":)"
                                         R"({"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],)"
                                         R"("images":[{"uri":")" + image_uri + R"("}],)";
    doc += R"("buffers":[{"uri":")" + buffer_uri + R"(","byteLength":80}],)"
           R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":72},{"buffer":0,"byteOffset":72,"byteLength":6}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
           R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
    return doc;
}

struct Case {
    const char* what;
    std::string scene;     // file name inside the temp folder
    int exit_code;
    std::string message;   // part of stderr
};

TEST(SpecialFiles, FifosDevicesAndFoldersNeverHang)
{
    if (!have_cpu_device()) GTEST_SKIP() << "no OpenCL CPU device";
    TempDir dir;
    ASSERT_EQ(mkfifo((dir / "pipe").c_str(), 0600), 0);
    std::filesystem::copy_file(std::filesystem::path(GC_BAD_CORPUS_DIR) / "tri_ok.bin", dir / "tri_ok.bin");
    std::filesystem::create_directory(dir / "folder.png");
    std::filesystem::create_symlink(dir / "pipe", dir / "pipe.obj");

    write_file(dir / "mtllib_fifo.obj", std::string("mtllib pipe\n") + k_triangle_obj + "f 1 2 3\n");
    write_file(dir / "texture_fifo.obj", std::string("mtllib tex.mtl\n") + k_triangle_obj + "usemtl t\nf 1 2 3\n");
    write_file(dir / "tex.mtl", "newmtl t\nKd 1 1 1\nmap_Kd pipe\n");
    write_file(dir / "texture_folder.obj", std::string("mtllib folder.mtl\n") + k_triangle_obj + "usemtl t\nf 1 2 3\n");
    write_file(dir / "folder.mtl", "newmtl t\nKd 1 1 1\nmap_Kd folder.png\n");
    write_file(dir / "buffer_fifo.gltf", triangle_gltf("pipe", ""));
    write_file(dir / "image_fifo.gltf", triangle_gltf("tri_ok.bin", "pipe"));
    write_file(dir / "image_device.gltf", triangle_gltf("tri_ok.bin", "/dev/zero"));

    const std::vector<Case> cases = {
        {"the scene is a FIFO", "pipe.obj", 3, "pipe.obj: is not a regular file (a device, pipe or socket)"},
        {".mtl library is a FIFO", "mtllib_fifo.obj", 0,
         "material library 'pipe' is not a regular file (a device, pipe or socket); using the default material"},
        {"texture is a FIFO", "texture_fifo.obj", 3, "texture 'pipe' is not a regular file (a device, pipe or socket)"},
        {"texture is a folder", "texture_folder.obj", 3, "folder.png' is a directory, not a file"},
        {"glTF buffer is a FIFO", "buffer_fifo.gltf", 3, "pipe: is not a regular file (a device, pipe or socket)"},
        {"glTF image is a FIFO", "image_fifo.gltf", 3, "image 0 'pipe': is not a regular file (a device, pipe or socket)"},
        // tinygltf resolves every uri against the scene's folder, absolute or not.
        {"glTF image is /dev/zero", "image_device.gltf", 3, "image 0 '/dev/zero': file not found"},
    };
    RunOptions options = cli_options();
    options.cwd = dir.path();
    options.timeout_seconds = 60.0;
    for (const Case& c : cases) {
        const RunResult r = run_process(cli_path(), {c.scene, "--spp", "1", "--res", "8x8", "--device", "cpu", "-o", "out.ppm"}, options);
        std::string shown = r.err;
        while (!shown.empty() && shown.back() == '\n') shown.pop_back();
        std::printf("  %s: %s -> %s (%.2f s)\n    %s\n", c.what, c.scene.c_str(), r.describe().c_str(), r.seconds, shown.c_str());
        EXPECT_FALSE(r.timed_out) << c.what << ": hung";
        EXPECT_EQ(r.signal, 0) << c.what;
        EXPECT_EQ(r.exit_code, c.exit_code) << c.what << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.what << ": expected '" << c.message << "' in:\n" << r.err;
        if (c.exit_code != 0) {
            EXPECT_FALSE(std::filesystem::exists(dir / "out.ppm")) << c.what << ": an image was written";
        }
        std::filesystem::remove(dir / "out.ppm");
    }
}

}  // namespace
}  // namespace gc::test
