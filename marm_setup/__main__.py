from marm_setup.cli import main

main()
