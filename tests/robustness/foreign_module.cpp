// A loadable library that is not a geocold-cl image module (it lacks gc_image_module_v1):
// image_module_test points GEOCOLD_IMAGE_MODULE at it.
extern "C" int gc_not_an_image_module() { return 0; }
