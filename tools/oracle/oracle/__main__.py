"""`python -m tools.oracle.oracle`: see the package's text."""

from tools.oracle.oracle.run import main

main()
