out.csg: \
	/tmp/dep/other.scad \
	/tmp/dep/lib\ a.scad \
	main.scad
