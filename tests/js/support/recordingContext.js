// A stand-in canvas 2D context for drawing tests in Node.

/** A stand-in 2D context that records what is drawn, with the fill or stroke style at the time. */
export function recordingContext() {

	const calls = [];
	const ctx = {
		calls, fillStyle: '', strokeStyle: '', lineWidth: 1, font: '', textAlign: '', textBaseline: '',
		setLineDash( dash ) {

			this.dash = dash;

		},
	};
	for ( const name of [ 'fillRect', 'strokeRect', 'arc', 'fillText', 'moveTo', 'lineTo', 'quadraticCurveTo', 'beginPath', 'fill', 'stroke', 'clearRect' ] ) {

		ctx[ name ] = function ( ...args ) {

			calls.push( { name, args, fillStyle: this.fillStyle, strokeStyle: this.strokeStyle, dash: this.dash ?? [] } );

		};

	}

	return ctx;

}
