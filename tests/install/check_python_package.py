"""The installed Python package (run_install_test.cmake): imported from the prefix alone, it renders."""
import sys

site = sys.argv[1]
sys.path.insert(0, site)
import fresnel  # noqa: E402

assert fresnel.__file__.startswith(site), fresnel.__file__
print(fresnel.__version__, fresnel.render(fresnel.load(), size=(16, 12)).shape)
