from marm_setup.cli.app import main

main()
